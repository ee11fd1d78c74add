# Board preset: Intel Programmable Acceleration Card with Arria 10 GX 1150 (2 x DDR4), board pac_a10 of the PAC stack.
set(RFRECON_FPGA_VENDOR intel)
set(RFRECON_FPGA_DEVICE_DEFAULT pac_a10)
set(RFRECON_FPGA_DESCRIPTION "Intel PAC, Arria 10 GX 1150")
# Parameters sized by the budget (scripts/fpga_budget.py, docs/fpga.md#resource-budget): rows of 2048 pixels, a 1080p
# projector's and a 2 MP camera's, with interleaves of about a third of the Stratix 10 estimates of the loops'
# latencies (R_int 66, R_fuse 18): II 3 by those estimates (scripts/fpga_latency.py), less at an Arria 10's clock.
set(RFRECON_PRESET_MAX_ROW_WIDTH 2048)
set(RFRECON_PRESET_INTEGRATE_INTERLEAVE 66)
set(RFRECON_PRESET_FUSE_INTERLEAVE 18)
# Dot spacings: the capture's default 8, 4 (16 frames) and 16 (isolated dots): each is two dividers in the compression.
set(RFRECON_PRESET_DOT_SPACINGS 4 8 16)
