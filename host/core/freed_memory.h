// For a process that scans again and again: the memory it frees kept for its next scan instead of handed back to the
// system, which would map, zero and fault it in again page by page (docs/api.md, "Scanning again and again").
#pragma once

namespace rfrecon {

// Process-wide, from the call on: glibc's malloc serves every block from its heaps, none from a mapping of its own
// (unmapped when freed, whatever its size: a 4096 x 2730 camera's images are 45 MB each), and no longer trims the
// heaps' free tops. A block larger than a thread's heap (64 MiB) that a thread other than the first allocates is still
// mapped on its own. Returns false, changing nothing, where malloc is not glibc's.
bool keep_freed_memory();

}  // namespace rfrecon
