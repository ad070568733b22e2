// Gazebo's physics on an rse world: loads a world's Gazebo terrain model
// (gazebo/rse_terrain/model.sdf) into gz-physics 5 (Debian's
// libignition-physics) the way gz-sim's Physics system does, drops the
// bodies listed in a file, steps them, and prints where they came to rest
// and how long a step took, beside the same bodies on a plane.
//
// Usage: harness ENGINE_PLUGIN MODEL_SDF DROPS SECONDS [--flat]
//   ENGINE_PLUGIN  e.g. /usr/lib/x86_64-linux-gnu/ign-physics-5/engine-plugins/libignition-physics-dartsim-plugin.so
//   MODEL_SDF      a world's gazebo/rse_terrain/model.sdf
//   DROPS          one body per line: `sphere R X Y Z ZFLAT` or
//                  `box HX HY HZ X Y Z ZFLAT` (ZFLAT: its start on the plane)
//   SECONDS        simulated time, at 1 kHz
//   --flat         also time the same bodies on the ground alone
// Output, one JSON object on stdout (flat_step_us: 0 without --flat):
//   {"step_us": .., "flat_step_us": .., "bodies": [[x, y, z, speed], ..]}
//
// gz-sim builds a model as the bare model, then each link, then each
// collision, attaching mesh collisions with the mesh feature: dartsim cannot
// build meshes from SDF ("Mesh construction from an SDF has not been
// implemented yet for dartsim"). So does this harness.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ignition/common/Mesh.hh>
#include <ignition/common/MeshManager.hh>
#include <ignition/math/eigen3/Conversions.hh>
#include <ignition/physics/FindFeatures.hh>
#include <ignition/physics/ForwardStep.hh>
#include <ignition/physics/FrameSemantics.hh>
#include <ignition/physics/RequestEngine.hh>
#include <ignition/physics/mesh/MeshShape.hh>
#include <ignition/physics/sdf/ConstructCollision.hh>
#include <ignition/physics/sdf/ConstructLink.hh>
#include <ignition/physics/sdf/ConstructModel.hh>
#include <ignition/physics/sdf/ConstructWorld.hh>
#include <ignition/plugin/Loader.hh>
#include <sdf/Collision.hh>
#include <sdf/Geometry.hh>
#include <sdf/Link.hh>
#include <sdf/Mesh.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <sdf/World.hh>

namespace physics = ignition::physics;

using Features = physics::FeatureList<
    physics::sdf::ConstructSdfWorld,
    physics::sdf::ConstructSdfModel,
    physics::sdf::ConstructSdfLink,
    physics::sdf::ConstructSdfCollision,
    physics::mesh::AttachMeshShapeFeature,
    physics::ForwardStep,
    physics::LinkFrameSemantics>;
using Engine = physics::Engine3dPtr<Features>;
using World = physics::World3dPtr<Features>;
using Link = physics::Link3dPtr<Features>;

[[noreturn]] static void fail(const std::string &message)
{
  std::cerr << "harness: " << message << std::endl;
  std::exit(2);
}

// `model://NAME/rest` → FOLDER/rest, FOLDER being the model's folder.
static std::string resolve(const std::string &uri, const std::string &folder)
{
  const std::string scheme = "model://";
  if (uri.rfind(scheme, 0) != 0)
    return folder + "/" + uri;
  const auto slash = uri.find('/', scheme.size());
  if (slash == std::string::npos)
    fail("mesh URI without a path: " + uri);
  return folder + uri.substr(slash);
}

// Builds `model` in `world` as gz-sim's Physics system does; its links.
static std::vector<Link> construct(World &world, const sdf::Model &model,
                                   const std::string &folder)
{
  sdf::Model bare;
  bare.SetName(model.Name());
  bare.SetRawPose(model.RawPose());
  bare.SetStatic(model.Static());
  auto built = world->ConstructModel(bare);
  std::vector<Link> links;
  for (uint64_t i = 0; i < model.LinkCount(); ++i)
  {
    const sdf::Link *from = model.LinkByIndex(i);
    sdf::Link link;
    link.SetName(from->Name());
    link.SetRawPose(from->RawPose());
    link.SetInertial(from->Inertial());
    auto l = built->ConstructLink(link);
    for (uint64_t c = 0; c < from->CollisionCount(); ++c)
    {
      const sdf::Collision *collision = from->CollisionByIndex(c);
      const sdf::Geometry *geometry = collision->Geom();
      if (geometry->Type() == sdf::GeometryType::MESH)
      {
        const std::string path = resolve(geometry->MeshShape()->Uri(), folder);
        const ignition::common::Mesh *mesh =
            ignition::common::MeshManager::Instance()->Load(path);
        if (mesh == nullptr)
          fail("cannot load the mesh " + path);
        l->AttachMeshShape(collision->Name(), *mesh,
                           ignition::math::eigen3::convert(collision->RawPose()));
      }
      else if (!l->ConstructCollision(*collision))
      {
        fail("cannot construct collision " + collision->Name());
      }
    }
    links.push_back(l);
  }
  return links;
}

static sdf::Root parse(const std::string &text)
{
  sdf::Root root;
  const auto errors = root.LoadSdfString(text);
  if (!errors.empty() || root.Model() == nullptr)
    fail("bad SDF: " + text);
  return root;
}

struct Drop
{
  std::string geometry;  // SDF geometry element
  double volume;
  double start[3];
  double flat_z;
};

static std::vector<Drop> read_drops(const std::string &path)
{
  std::ifstream in(path);
  if (!in)
    fail("cannot read " + path);
  std::vector<Drop> drops;
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string shape;
    if (!(words >> shape))
      continue;
    Drop d;
    std::ostringstream geometry;
    if (shape == "sphere")
    {
      double r;
      words >> r;
      geometry << "<sphere><radius>" << r << "</radius></sphere>";
      d.volume = 4.0 / 3.0 * M_PI * r * r * r;
    }
    else if (shape == "box")
    {
      double h[3];
      words >> h[0] >> h[1] >> h[2];
      geometry << "<box><size>" << 2 * h[0] << " " << 2 * h[1] << " "
               << 2 * h[2] << "</size></box>";
      d.volume = 8 * h[0] * h[1] * h[2];
    }
    else
    {
      fail("unknown shape in " + path + ": " + line);
    }
    words >> d.start[0] >> d.start[1] >> d.start[2] >> d.flat_z;
    if (!words)
      fail("bad line in " + path + ": " + line);
    d.geometry = geometry.str();
    drops.push_back(d);
  }
  return drops;
}

// A free body of density 500 kg/m³ (the rapier smoke test's), its
// inertia that of a sphere of its volume: enough for a body at rest.
static std::string body_sdf(const Drop &d, std::size_t i, double z)
{
  const double mass = 500.0 * d.volume;
  const double r = std::cbrt(3 * d.volume / (4 * M_PI));
  const double inertia = 0.4 * mass * r * r;
  std::ostringstream s;
  s << "<sdf version='1.9'><model name='body_" << i << "'><pose>" << d.start[0]
    << " " << d.start[1] << " " << z << " 0 0 0</pose><link name='link'>"
    << "<inertial><mass>" << mass << "</mass><inertia><ixx>" << inertia
    << "</ixx><iyy>" << inertia << "</iyy><izz>" << inertia
    << "</izz></inertia></inertial><collision name='collision'><geometry>"
    << d.geometry << "</geometry></collision></link></model></sdf>";
  return s.str();
}

static const char *GROUND =
    "<sdf version='1.9'><model name='ground_plane'><static>true</static>"
    "<link name='link'><collision name='collision'><geometry><plane>"
    "<normal>0 0 1</normal><size>1000 1000</size></plane></geometry>"
    "</collision></link></model></sdf>";

struct Run
{
  double step_us;
  std::vector<Link> bodies;
};

// A world with the ground, the terrain (none for the flat control) and the
// bodies, stepped `steps` times at 1 kHz.
static Run simulate(Engine &engine, const sdf::Model *terrain,
                    const std::string &folder, const std::vector<Drop> &drops,
                    int steps)
{
  // From SDF, as gz-sim does, for its gravity: an empty Bullet world
  // pulls along -y.
  sdf::World empty;
  empty.SetName("rse");
  empty.SetGravity({0, 0, -9.81});
  World world = engine->ConstructWorld(empty);
  construct(world, *parse(GROUND).Model(), folder);
  if (terrain != nullptr)
    construct(world, *terrain, folder);
  Run run;
  for (std::size_t i = 0; i < drops.size(); ++i)
  {
    const double z = terrain != nullptr ? drops[i].start[2] : drops[i].flat_z;
    run.bodies.push_back(
        construct(world, *parse(body_sdf(drops[i], i, z)).Model(), folder)[0]);
  }
  physics::ForwardStep::Input input;
  physics::ForwardStep::State state;
  physics::ForwardStep::Output output;
  input.Get<std::chrono::steady_clock::duration>() =
      std::chrono::milliseconds(1);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i)
    world->Step(output, state, input);
  const std::chrono::duration<double, std::micro> spent =
      std::chrono::steady_clock::now() - start;
  run.step_us = spent.count() / std::max(steps, 1);
  return run;
}

int main(int argc, char **argv)
{
  const bool with_flat = argc == 6 && std::string(argv[5]) == "--flat";
  if (argc != 5 && !with_flat)
    fail("usage: harness ENGINE_PLUGIN MODEL_SDF DROPS SECONDS [--flat]");
  const std::string plugin_path = argv[1];
  const std::string model_path = argv[2];
  const int steps = static_cast<int>(std::lround(std::stod(argv[4]) * 1000));

  ignition::plugin::Loader loader;
  if (loader.LoadLib(plugin_path).empty())
    fail("no plugin in " + plugin_path);
  const auto names = physics::FindFeatures3d<Features>::From(loader);
  if (names.empty())
    fail(plugin_path + " lacks a feature the harness needs");
  Engine engine =
      physics::RequestEngine3d<Features>::From(loader.Instantiate(*names.begin()));

  sdf::Root root;
  const auto errors = root.Load(model_path);
  if (!errors.empty() || root.Model() == nullptr)
    fail("cannot load " + model_path);
  const std::string folder = model_path.substr(0, model_path.rfind('/'));
  const std::vector<Drop> drops = read_drops(argv[3]);

  Run rse = simulate(engine, root.Model(), folder, drops, steps);
  const double flat_step_us =
      with_flat ? simulate(engine, nullptr, folder, drops, steps).step_us : 0;

  std::printf("{\"step_us\": %.3f, \"flat_step_us\": %.3f, \"bodies\": [",
              rse.step_us, flat_step_us);
  for (std::size_t i = 0; i < rse.bodies.size(); ++i)
  {
    const auto data = rse.bodies[i]->FrameDataRelativeToWorld();
    const auto p = data.pose.translation();
    std::printf("%s[%.6f, %.6f, %.6f, %.6f]", i ? ", " : "", p.x(), p.y(),
                p.z(), data.linearVelocity.norm());
  }
  std::printf("]}\n");
  return 0;
}
