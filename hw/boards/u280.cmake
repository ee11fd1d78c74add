# Board preset: AMD Alveo U280 (8 GB HBM2 in 32 pseudo-channels, 2 x DDR4), Vitis 2022.2 XDMA shell; banks in u280.cfg.
set(RFRECON_FPGA_VENDOR xilinx)
set(RFRECON_FPGA_DEVICE_DEFAULT xilinx_u280_gen3x16_xdma_1_202211_1)
set(RFRECON_FPGA_DESCRIPTION "AMD Alveo U280")
set(RFRECON_FPGA_LINK_CONFIG ${CMAKE_CURRENT_LIST_DIR}/u280.cfg)
# Unsupported: the kernels do not fit this board at the default parameters (scripts/fpga_budget.py, docs/fpga.md).
set(RFRECON_FPGA_SUPPORTED OFF)
