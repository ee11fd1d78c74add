# Board preset: Intel Programmable Acceleration Card with Arria 10 GX 1150 (2 x DDR4), board pac_a10 of the PAC stack.
set(RFRECON_FPGA_VENDOR intel)
set(RFRECON_FPGA_DEVICE_DEFAULT pac_a10)
set(RFRECON_FPGA_DESCRIPTION "Intel PAC, Arria 10 GX 1150")
# Unsupported: the kernels do not fit this board at the default parameters (scripts/fpga_budget.py, docs/fpga.md).
set(RFRECON_FPGA_SUPPORTED OFF)
