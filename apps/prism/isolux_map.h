#pragma once
// A false-colour map of illuminance over a grid of meter points, as lighting software draws one:
// the readings interpolated bilinearly between the points and coloured on a perceptual scale,
// isolux lines at round levels, and a legend naming them. For `prism measure --grid`.

#include <filesystem>
#include <string>
#include <vector>

namespace prism {

// `lux` holds nx × ny readings, row by row (row 0 at the top of the map).
void write_isolux_png(const std::filesystem::path& file, int nx, int ny, const std::vector<double>& lux,
                      const std::string& title);

}  // namespace prism
