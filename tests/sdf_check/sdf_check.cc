// sdf_check: strict validation of SDF files with libsdformat (what `ign sdf -k`
// does, but failing on unknown elements and warnings too), plus the checks
// rse's worlds promise: SDF version <= 1.9, and every mesh URI resolving to
// an existing file, with model:// looked up beside the file.
//
// Usage: sdf_check FILE...   Exit 0 if every file passes, 1 otherwise.

#include <sdf/sdf.hh>

#include <filesystem>
#include <iostream>
#include <string>

namespace fs = std::filesystem;

namespace {

// Whether the file a mesh URI names exists: model://NAME/rest in the checked
// file's folder (a world beside its models) or the folder above it (a
// model.sdf inside its model folder); a relative path against the folder.
bool resolves(const std::string &uri, const fs::path &folder) {
  const std::string scheme = "model://";
  if (uri.rfind(scheme, 0) != 0) return fs::is_regular_file(folder / uri);
  const std::string rest = uri.substr(scheme.size());
  return fs::is_regular_file(folder / rest) ||
         fs::is_regular_file(folder.parent_path() / rest);
}

bool checkMeshes(const sdf::Model *model, const fs::path &folder,
                 const std::string &file) {
  bool ok = true;
  for (uint64_t l = 0; l < model->LinkCount(); ++l) {
    const sdf::Link *link = model->LinkByIndex(l);
    auto check = [&](const sdf::Geometry *geometry) {
      if (geometry == nullptr || geometry->MeshShape() == nullptr) return;
      const std::string uri = geometry->MeshShape()->Uri();
      if (uri.rfind("/", 0) == 0) {
        std::cerr << file << ": absolute mesh URI " << uri << "\n";
        ok = false;
      } else if (!resolves(uri, folder)) {
        std::cerr << file << ": mesh " << uri << " not found\n";
        ok = false;
      }
    };
    for (uint64_t c = 0; c < link->CollisionCount(); ++c)
      check(link->CollisionByIndex(c)->Geom());
    for (uint64_t v = 0; v < link->VisualCount(); ++v)
      check(link->VisualByIndex(v)->Geom());
  }
  for (uint64_t m = 0; m < model->ModelCount(); ++m)
    ok = checkMeshes(model->ModelByIndex(m), folder, file) && ok;
  return ok;
}

bool checkFile(const std::string &file) {
  const fs::path folder = fs::absolute(file).parent_path();
  sdf::ParserConfig config;
  config.SetWarningsPolicy(sdf::EnforcementPolicy::ERR);
  config.SetUnrecognizedElementsPolicy(sdf::EnforcementPolicy::ERR);
  config.SetDeprecatedElementsPolicy(sdf::EnforcementPolicy::ERR);
  config.AddURIPath("model://", folder.string());
  config.SetFindCallback([](const std::string &) { return std::string(); });

  sdf::Root root;
  const sdf::Errors errors = root.Load(file, config);
  if (!errors.empty()) {
    for (const auto &e : errors) std::cerr << file << ": " << e << "\n";
    return false;
  }
  // Root::Version() is the version after conversion; read the file's own.
  sdf::SDFPtr raw(new sdf::SDF());
  sdf::init(raw);
  sdf::Errors rawErrors;
  if (!sdf::readFile(file, config, raw, rawErrors) || !rawErrors.empty()) {
    std::cerr << file << ": cannot read\n";
    return false;
  }
  const std::string version = raw->OriginalVersion();
  if (version.empty() || std::stod(version) > 1.9 + 1e-9) {
    std::cerr << file << ": SDF version '" << version << "', want <= 1.9\n";
    return false;
  }
  bool ok = true;
  for (uint64_t w = 0; w < root.WorldCount(); ++w) {
    const sdf::World *world = root.WorldByIndex(w);
    for (uint64_t m = 0; m < world->ModelCount(); ++m)
      ok = checkMeshes(world->ModelByIndex(m), folder, file) && ok;
  }
  if (root.Model() != nullptr) ok = checkMeshes(root.Model(), folder, file) && ok;
  return ok;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 2) {
    std::cerr << "usage: sdf_check FILE...\n";
    return 2;
  }
  int failed = 0;
  for (int i = 1; i < argc; ++i) failed += checkFile(argv[i]) ? 0 : 1;
  return failed == 0 ? 0 : 1;
}
