"""The FPGA devices of the board presets: memory-block shapes, block and DSP counts, SLRs, and the shell's share.

Numbers, from the vendors' public data sheets and guides:
  Intel M20K (20 Kbit): 512 x 40, 1K x 20, 2K x 10 in simple dual-port mode (one read, one write port); true
    dual-port (two read/write ports) up to 1K x 20. Intel Stratix 10 / Arria 10 Embedded Memory User Guides.
  Arria 10 GX 1150: 2,713 M20K, 1,518 DSP blocks. Intel Arria 10 Device Overview (A10-OVERVIEW), GX table.
  Stratix 10 GX 2800 (Bittware 520N) and SX 2800 (PAC D5005): 11,721 M20K, 5,760 DSP blocks. Intel Stratix 10 GX/SX
    Device Overview (S10-OVERVIEW).
  AMD BRAM36 (36 Kbit): true dual-port 32K x 1, 16K x 2, 8K x 4, 4K x 9, 2K x 18, 1K x 36; simple dual-port also
    512 x 72. URAM (288 Kbit): 4K x 72, two ports. UltraScale Architecture Memory Resources (UG573).
  Alveo U250 (XCU250, 4 SLRs): 2,688 BRAM36, 1,280 URAM, 12,288 DSP, a quarter per SLR; DDR[n] in SLR n, the
    platform's static region in SLR1. Alveo U250 data sheet (DS962); floorplan in UG1120, U250 Gen3x16 XDMA 4.1.
  Alveo U280 (XCU280, 3 SLRs): 2,016 BRAM36, 960 URAM, 9,024 DSP, a third per SLR; the HBM and DDR[0] in SLR0,
    DDR[1] in SLR1, the static region in SLR0. Alveo U280 data sheet (DS963); floorplan in UG1120.
Shell share (an assumption, to be replaced by the vendor report's figures):
  Intel: the BSP's board interface (PCIe, DMA, memory controllers; on the PAC cards the FIM) takes 15% of the M20K
    and DSP blocks. aoc's report.html gives the real figure in its "Board interface" row.
  AMD: the SLR that holds the platform's static region keeps half of its resources (the order of UG1393's "Resource
    Availability" example, 326 BRAMs in that SLR against 638 in the others), and every SLR keeps 10% for the
    system's infrastructure and routing (UG1393, "Determining Where to Place the Kernels"). `platforminfo` of the
    platform gives the real per-SLR figures.
"""
import math
import re

# Block shapes, (depth in words, width in bits).
M20K_SIMPLE = ((512, 40), (1024, 20), (2048, 10))
M20K_TRUE = ((1024, 20), (2048, 10))
BRAM36_TRUE = ((1024, 36), (2048, 18), (4096, 9), (8192, 4), (16384, 2), (32768, 1))
BRAM36_SIMPLE = ((512, 72),) + BRAM36_TRUE
URAM = ((4096, 72),)

# Block kind -> (shapes with one read and one write port, shapes with two read/write ports).
SHAPES = {"M20K": (M20K_SIMPLE, M20K_TRUE), "BRAM36": (BRAM36_SIMPLE, BRAM36_TRUE), "URAM": (URAM, URAM)}

INTEL_SHELL_SHARE = 0.15
AMD_STATIC_SLR_KEEPS = 0.5
AMD_INFRASTRUCTURE_SHARE = 0.10


def blocks(words, width_bits, kind, true_dual_port):
    """Blocks of `kind` that hold `words` words of `width_bits`, in the cheapest shape of the port mode."""
    shapes = SHAPES[kind][1 if true_dual_port else 0]
    return min(math.ceil(words / depth_words) * math.ceil(width_bits / shape_bits)
               for depth_words, shape_bits in shapes)


class Device:
    """One FPGA: `totals` {block kind or "DSP": count on the device}, `slrs` their split (one SLR for Intel)."""

    def __init__(self, name, vendor, totals, slr_count=1, static_slr=None, bank_slr=None):
        self.name = name
        self.vendor = vendor
        self.totals = totals
        self.slr_count = slr_count
        self.static_slr = static_slr
        self.bank_slr = bank_slr or (lambda bank: 0)

    def memory_kinds(self):
        return [kind for kind in self.totals if kind != "DSP"]

    def available(self, kind, slr=None):
        """Blocks of `kind` (or DSPs) left to the kernels, in one SLR or (slr None) in all, after the shell."""
        if self.vendor == "intel":
            return math.floor(self.totals[kind] * (1 - INTEL_SHELL_SHARE))
        slrs = range(self.slr_count) if slr is None else [slr]
        per_slr = self.totals[kind] / self.slr_count
        return sum(math.floor(per_slr * (AMD_STATIC_SLR_KEEPS if s == self.static_slr else 1.0)
                              * (1 - AMD_INFRASTRUCTURE_SHARE)) for s in slrs)

    def shell_note(self, slr=None):
        """How available() counts, in words."""
        if self.vendor == "intel":
            return f"less {INTEL_SHELL_SHARE:.0%} for the BSP"
        infrastructure = f"{AMD_INFRASTRUCTURE_SHARE:.0%} for infrastructure"
        if slr is None:
            return f"less half of SLR{self.static_slr} for the static region and {infrastructure} in each SLR"
        if slr == self.static_slr:
            return f"less half for the static region and {infrastructure}"
        return f"less {infrastructure}"


def _u250_bank(bank):
    found = re.match(r"DDR\[(\d+)\]", bank)
    return int(found[1]) if found else 0


def _u280_bank(bank):
    found = re.match(r"DDR\[(\d+)\]", bank)
    return int(found[1]) if found else 0  # HBM pseudo-channels and PLRAM of SLR0


ARRIA10_GX1150 = Device("Arria 10 GX 1150", "intel", {"M20K": 2713, "DSP": 1518})
STRATIX10_2800 = Device("Stratix 10 GX/SX 2800", "intel", {"M20K": 11721, "DSP": 5760})
ALVEO_U250 = Device("Alveo U250 (XCU250)", "xilinx", {"BRAM36": 2688, "URAM": 1280, "DSP": 12288}, slr_count=4,
                    static_slr=1, bank_slr=_u250_bank)
ALVEO_U280 = Device("Alveo U280 (XCU280)", "xilinx", {"BRAM36": 2016, "URAM": 960, "DSP": 9024}, slr_count=3,
                    static_slr=0, bank_slr=_u280_bank)

# A preset's device, found from its RFRECON_FPGA_DESCRIPTION (hw/boards/<name>.cmake).
BY_DESCRIPTION = (("Arria 10 GX 1150", ARRIA10_GX1150), ("Stratix 10 GX 2800", STRATIX10_2800),
                  ("Stratix 10 SX 2800", STRATIX10_2800), ("Alveo U250", ALVEO_U250), ("Alveo U280", ALVEO_U280))


def device_of(description):
    for key, device in BY_DESCRIPTION:
        if key in description:
            return device
    return None
