// `rfrecon simulate`: renders a built-in or file scene with the synthetic rig into a capture + ground-truth directory.
#include <iostream>
#include <optional>

#include <spdlog/spdlog.h>

#include "host/capture/dot_grid.h"
#include "host/capture/pattern_family.h"
#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/cli/protocol_option.h"
#include "host/cli/size_option.h"
#include "sim/builtin_rigs.h"
#include "sim/builtin_scenes.h"
#include "sim/simulate.h"

namespace rfrecon::cli {

namespace {
struct SimulateCommandOptions {
  std::string scene;
  std::string rig;
  std::string out;
  std::optional<unsigned long long> seed;
  bool force = false;
  bool list = false;
  std::string camera_size;
  std::string projector_size;
  std::optional<int> supersample;
  std::optional<int> interreflection;
  std::string family;
  std::shared_ptr<std::map<std::string, int>> parameters = std::make_shared<std::map<std::string, int>>();
  std::optional<int> dot_spacing;
  std::string format;
  int threads = 0;
};

void run_simulate(const SimulateCommandOptions& o) {
  if (o.list) {
    std::cout << "scenes (--scene):\n";
    for (const auto& info : sim::builtin_scenes()) std::cout << "  " << info.name << "\t" << info.description << "\n";
    std::cout << "rigs (--rig; default " << sim::kDefaultRig << "):\n";
    for (const auto& info : sim::builtin_rigs()) std::cout << "  " << info.name << "\t" << info.description << "\n";
    return;
  }
  if (o.scene.empty()) throw CLI::RequiredError("--scene (a built-in name, see --list, or a scene file)");
  if (o.out.empty()) throw CLI::RequiredError("--output");
  sim::SceneChanges changes;
  changes.rig = o.rig;
  if (!o.camera_size.empty()) changes.camera_size = parse_size(o.camera_size, "--camera");
  if (!o.projector_size.empty()) changes.projector_size = parse_size(o.projector_size, "--projector");
  changes.supersample = o.supersample;
  changes.interreflection = o.interreflection;
  changes.family = o.family;
  changes.parameters = *o.parameters;
  changes.dot_spacing = o.dot_spacing;
  changes.seed = o.seed;
  changes.format = o.format;
  const sim::Scene scene = sim::resolve_scene(o.scene, changes);
  spdlog::info("simulate: scene '{}', camera {}x{}, projector {}x{}, supersample {}x{}, seed {}", scene.name,
               scene.camera.size.width, scene.camera.size.height, scene.projector.size.width,
               scene.projector.size.height, scene.render.supersample, scene.render.supersample, scene.render.seed);
  sim::simulate(scene, o.out, {o.threads, o.force, sim::scene_files(o.scene)});
  spdlog::info("simulate: wrote {}", o.out);
}
}  // namespace

void add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateCommandOptions>();
  auto* command = app.add_subcommand("simulate", "Render a synthetic projector-camera capture with ground truth");
  command->add_option("--scene", o->scene, "Built-in scene name (see --list) or scene JSON file");
  command->add_option("--rig", o->rig, "Built-in rig (see --list) replacing the scene's camera and projector");
  command->add_option("-o,--output", o->out, "Output directory (must not exist or be empty, unless --force)");
  command->add_option("--seed", o->seed, "Noise seed (default: the scene's render.seed, 1)");
  command->add_flag("--force", o->force, "Replace a non-empty output directory");
  command->add_flag("--list", o->list, "Print the built-in scenes and rigs and exit");
  command->add_option("--camera", o->camera_size, "Camera resolution WxH (keeps the field of view)");
  command->add_option("--projector", o->projector_size, "Projector resolution WxH (keeps the field of view)");
  command->add_option("--supersample", o->supersample, "Sub-pixel rays per camera pixel side (default: scene's, 4)")
      ->check(CLI::Range(1, 32));
  command
      ->add_option("--interreflection", o->interreflection,
                   "One-bounce interreflection rays per sub-pixel sample, 0 = off (default: the scene's)")
      ->check(CLI::Range(0, 1024));
  command->add_option("--family", o->family, "Pattern family of the capture (default: the scene's, graycode)")
      ->check(CLI::IsMember(capture::pattern_family_names()));
  add_family_parameter_options(*command, o->parameters);
  command
      ->add_option("--dot-spacing", o->dot_spacing,
                   "Dot grid spacing s of the capture (s x s frames after the family's patterns); 0 = no dot grid "
                   "(default: the scene's)")
      ->check(zero_or_range(2, capture::kMaxDotSpacing, "no dot grid"));
  command
      ->add_option("--format", o->format,
                   "Frame files: tiff (uncompressed, read at memory speed) or png (default: the scene's, tiff)")
      ->check(CLI::IsMember({"tiff", "png"}));
  command->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  command->callback([o] { run_simulate(*o); });
}

}  // namespace rfrecon::cli
