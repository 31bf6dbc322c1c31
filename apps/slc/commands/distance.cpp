// slc distance: signed distance and nearest point of each point of a CSV file.
#include "commands/commands.hpp"

namespace slc::cli {
void add_distance_command(CLI::App&) {}
void add_render_command(CLI::App&) {}
void add_tree_command(CLI::App&) {}
}  // namespace slc::cli
