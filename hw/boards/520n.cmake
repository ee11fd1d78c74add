# Board preset: Bittware 520N (Intel Stratix 10 GX 2800, 4 x DDR4), BSP board p520_max_sg280l, Intel FPGA SDK 19.x-22.4.
set(RFRECON_FPGA_VENDOR intel)
set(RFRECON_FPGA_DEVICE_DEFAULT p520_max_sg280l)  # p520_hpc_sg280l with Bittware's HPC BSP
set(RFRECON_FPGA_DESCRIPTION "Bittware 520N, Stratix 10 GX 2800")
# Dot spacings: the capture's default 8, 4 (16 frames) and 16 (isolated dots): each is two dividers in the compression.
set(RFRECON_PRESET_DOT_SPACINGS 4 8 16)
