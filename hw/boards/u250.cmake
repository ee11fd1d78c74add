# Board preset: AMD Alveo U250 (4 x DDR4 banks), XDMA shell of Vitis 2022.1/2022.2; memory banks in u250.cfg.
set(RFRECON_FPGA_VENDOR xilinx)
set(RFRECON_FPGA_DEVICE_DEFAULT xilinx_u250_gen3x16_xdma_4_1_202210_1)
set(RFRECON_FPGA_DESCRIPTION "AMD Alveo U250")
set(RFRECON_FPGA_LINK_CONFIG ${CMAKE_CURRENT_LIST_DIR}/u250.cfg)
# Parameters sized by the budget (scripts/fpga_budget.py, docs/fpga.md#resource-budget): rows of at most 2048 pixels,
# so that each depth kernel's on-chip rows fit one SLR (the link configuration places them); R_fuse 40, above the
# fusion's forward-sweep latency at 300 MHz, for II 1 (scripts/fpga_latency.py).
set(RFRECON_PRESET_MAX_ROW_WIDTH 2048)
set(RFRECON_PRESET_FUSE_INTERLEAVE 40)
# Dot spacings: the capture's default 8, 4 (16 frames) and 16 (isolated dots): each is two dividers in the compression.
set(RFRECON_PRESET_DOT_SPACINGS 4 8 16)
