#pragma once
// The subcommands of the `prism` executable; each registers its options and its action.

#include <CLI/CLI.hpp>

namespace prism {

void add_render_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_farm_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_fresnel_command(CLI::App& app);
void add_converge_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_measure_command(CLI::App& app);
void add_bench_command(CLI::App& app);  // bench rays; registers the other bench commands too
void add_bench_features_command(CLI::App* bench);
void add_bench_instances_command(CLI::App* bench);
void add_bench_light_tree_command(CLI::App* bench);

}  // namespace prism
