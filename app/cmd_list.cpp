// glint list — every scene and variant, with a line on what each shows.
#include "common.h"

#include "glint/core/error.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

namespace glint::app {

Command listCommand(CLI::App& app, const GlobalOptions&) {
  auto* cmd = app.add_subcommand("list", "List every scene and variant with what it shows");
  auto names = std::make_shared<bool>(false);
  auto filter = std::make_shared<std::string>();
  cmd->add_flag("--names", *names, "Only the full names (scene/variant), one per line, for scripts");
  cmd->add_option("filter", *filter, "Show only variants whose name contains this text");
  return Command{.run = [names, filter] {
    const auto& registry = scenes::Registry::builtin();
    if (registry.match(*filter).empty()) {
      fail(ErrorKind::Usage, "no scene or variant name contains '{}' (`glint list` shows them all)", *filter);
    }
    if (*names) {
      for (const auto& ref : registry.match(*filter)) fmt::print("{}\n", ref.fullName());
      return 0;
    }
    for (const auto& scene : registry.scenes()) {
      std::vector<int> shown;
      for (int v = 0; v < int(scene.variants.size()); ++v) {
        const auto full = scene.name + "/" + scene.variants[std::size_t(v)].name;
        if (filter->empty() || full.find(*filter) != std::string::npos) shown.push_back(v);
      }
      if (shown.empty()) continue;
      fmt::print("{}  ({}x{}{})\n  {}\n", scene.name, scene.defaultSize.x, scene.defaultSize.y,
                 scene.profile == gl::Profile::Compatibility ? ", compatibility profile" : "", scene.summary);
      for (int v : shown) {
        const auto& variant = scene.variants[std::size_t(v)];
        fmt::print("    {:<14} {}\n", variant.name, variant.description);
      }
    }
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app
