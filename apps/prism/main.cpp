// prism: the command-line front end. Errors in input print one clear message and exit with 1;
// usage errors exit with 2.

#include <cstdio>
#include <new>

#include "apps/prism/commands.h"
#include "core/base/error.h"

int main(int argc, char** argv) {
  CLI::App app("Prism: a spectral path tracer (glTF 2.0 in, scene-referred OpenEXR out)", "prism");
  app.set_version_flag("--version", "Prism " PRISM_VERSION);
  app.require_subcommand(1);
  prism::add_render_command(app);
  prism::add_merge_command(app);
  prism::add_farm_command(app);
  prism::add_info_command(app);
  prism::add_fresnel_command(app);
  prism::add_converge_command(app);
  prism::add_compare_command(app);
  prism::add_measure_command(app);
  prism::add_bench_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the message, or the help / version
    return code == 0 ? 0 : 2;
  } catch (const prism::Error& e) {
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "prism: error: out of memory (a smaller image, or --max-memory to refuse such work up front)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
