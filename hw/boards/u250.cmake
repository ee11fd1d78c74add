# Board preset: AMD Alveo U250 (4 x DDR4 banks), XDMA shell of Vitis 2022.1/2022.2; memory banks in u250.cfg.
set(RFRECON_FPGA_VENDOR xilinx)
set(RFRECON_FPGA_DEVICE_DEFAULT xilinx_u250_gen3x16_xdma_4_1_202210_1)
set(RFRECON_FPGA_DESCRIPTION "AMD Alveo U250")
set(RFRECON_FPGA_LINK_CONFIG ${CMAKE_CURRENT_LIST_DIR}/u250.cfg)
# Unsupported: the kernels do not fit this board at the default parameters (scripts/fpga_budget.py, docs/fpga.md).
set(RFRECON_FPGA_SUPPORTED OFF)
