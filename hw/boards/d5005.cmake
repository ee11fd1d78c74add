# Board preset: Intel FPGA PAC D5005 (Stratix 10 SX 2800, 4 x DDR4), board pac_s10_dc of the PAC stack.
set(RFRECON_FPGA_VENDOR intel)
set(RFRECON_FPGA_DEVICE_DEFAULT pac_s10_dc)
set(RFRECON_FPGA_DESCRIPTION "Intel FPGA PAC D5005, Stratix 10 SX 2800")
# Dot spacings: the capture's default 8, 4 (16 frames) and 16 (isolated dots): each is two dividers in the compression.
set(RFRECON_PRESET_DOT_SPACINGS 4 8 16)
