// `rfrecon transport` as a library call: a capture directory to T.h5, with stage timings and per-device shares.
#pragma once

#include <filesystem>
#include <vector>

#include "host/cl/entry_choice.h"
#include "host/transport/capture_views.h"
#include "host/transport/compute_transport.h"
#include "host/transport/pixel_outcomes.h"
#include "host/transport/transport_file.h"

namespace rfrecon::pipeline {

struct TransportRequest {
  std::filesystem::path capture_dir;
  transport::CaptureSource source;
  transport::TransportSetup setup;           // K and thresholds
  cl::EntryChoice entries;                   // kernel entry per device (default auto: cl::preferred_entry of each)
  int readers = transport::kDefaultReaders;  // threads reading frames ahead of the devices
  int deflate_level = transport::kDefaultDeflateLevel;  // T.h5's zlib level, 0 for none
  std::filesystem::path output;                         // T.h5, written atomically
  std::filesystem::path summary;                        // optional JSON of timings, shares and pixel counts
  std::filesystem::path maps;  // optional directory: decoded.png and outcomes.png (host/pipeline/transport_maps.h)
  bool force = false;          // replace existing output, summary and maps
};

struct TransportFileRun {
  transport::TransportRun run;               // timings include "write T.h5"
  transport::PixelOutcomeCounts outcomes{};  // decoded: the pixels with a correspondence
  std::size_t decoded_pixels() const { return outcomes[static_cast<std::size_t>(transport::PixelOutcome::kDecoded)]; }
  double total_seconds = 0.0;
};

// The transport stage of transport_capture on frames from any source, without its files: checks the memory T needs
// first, and throws ProcessingError (naming frames.name()) when no pixel decodes.
TransportFileRun transport_frames(const capture::FrameSource& frames, const capture::CaptureManifest& manifest,
                                  const transport::TransportSetup& setup, const cl::EntryChoice& entries, int readers,
                                  std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

// Decodes and compresses the capture on `devices` and writes T.h5 (and the summary and maps), all renamed into
// place only once all are written. Throws UsageError (before any work) for an output that check_output_file refuses (an
// input of the capture, a device, an existing file without force) and for a per-device entry list whose length is not
// the device count, InputError for a bad capture (naming the file), ProcessingError when no pixel decodes, OutputError
// when an output cannot be written, and sched::AllDevicesFailed when no device is left.
TransportFileRun transport_capture(const TransportRequest& request, std::vector<cl::DeviceContext>& devices,
                                   cl::ProgramCache& programs);

}  // namespace rfrecon::pipeline
