// The projector as a borderless full-screen SDL2 window on one display, showing each pattern pixel for pixel and
// presenting it at the vertical sync.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "host/acquire/projector.h"

namespace rfrecon::drivers {

// Opens a window covering display `display_index` (SDL's numbering, as `rfrecon capture --list-displays` prints).
// Throws HardwareError when there is no display server, or no such display (the message lists those there are).
std::unique_ptr<acquire::Projector> open_sdl_projector(int display_index);

// One line per display SDL sees: index, name, bounds and refresh rate; throws HardwareError without a display server.
std::vector<std::string> list_displays();

}  // namespace rfrecon::drivers
