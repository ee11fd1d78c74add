// For a process that scans again and again: the memory it frees kept for its next scan instead of handed back to the
// system, which would map, zero and fault it in again page by page (docs/api.md, "Scanning again and again").
#pragma once

namespace rfrecon {

// Process-wide, from the call on: glibc's malloc serves blocks of up to 32 MiB from its heaps (not from mappings of
// their own, unmapped when freed) and no longer trims the heaps' free tops. Returns false, changing nothing, where
// malloc is not glibc's. Larger blocks (a transport's rows: hand `storage` to compute_transport_on_devices) are still
// mapped on their own.
bool keep_freed_memory();

}  // namespace rfrecon
