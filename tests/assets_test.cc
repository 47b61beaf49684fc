// Loading MJCF text with files given in memory (LoadXmlString's `assets`, as MuJoCo's
// MjModel.from_xml_string(xml, assets)): included files, attached models and mesh files
// come from the assets, matched by file name whatever the folders and case, before the
// disk. A model loaded this way equals the one loaded from the same files on disk.
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab {
namespace {

namespace fs = std::filesystem;

// A file of the repository, as bytes.
std::string RepoBytes(const std::string& relative) {
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/" + relative, std::ios::binary);
  EXPECT_TRUE(in.good()) << "missing " << relative;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A folder of files written by a test, below the test's temporary folder.
class Folder {
 public:
  explicit Folder(const std::string& name) : dir_(fs::path(testing::TempDir()) / name) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string Write(const std::string& relative, const std::string& bytes) const {
    fs::path path = dir_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }

 private:
  fs::path dir_;
};

// The main file's name for loads from memory: its folder does not exist, so nothing
// it refers to can come from disk.
const char kMemoryFile[] = "simlab_in_memory_only/main.xml";

// The scene: an include (in the world body), a model attached from a file (the lesson's
// gripper) and two meshes (binary STL, OBJ) in meshdir.
const char kScene[] = R"(<mujoco model="assets">
  <compiler meshdir="meshes"/>
  <asset>
    <model name="gripper" file="models/hand.xml"/>
    <mesh name="box" file="box.stl"/>
    <mesh name="shape" file="shape.obj" scale="2 1 1"/>
  </asset>
  <worldbody>
    <include file="parts/floor.xml"/>
    <body name="carriage" pos="0 0 0.5">
      <joint name="lift" type="slide" axis="0 0 1"/>
      <geom name="carriage" type="mesh" mesh="box" density="800"/>
      <attach model="gripper" body="palm" prefix="gripper/"/>
    </body>
    <body name="block" pos="0.3 0 0.1">
      <freejoint/>
      <geom name="block" type="mesh" mesh="shape"/>
    </body>
  </worldbody>
</mujoco>
)";

const char kFloor[] = R"(<mujoco>
  <geom name="floor" type="plane" size="1 1 0.1"/>
</mujoco>
)";

// The scene's files by their paths below the main file's folder.
std::vector<std::pair<std::string, std::string>> SceneFiles() {
  return {{"parts/floor.xml", kFloor},
          {"models/hand.xml", RepoBytes("models/gripper.xml")},
          {"meshes/box.stl", RepoBytes("tests/meshes/assets/box.stl")},
          {"meshes/shape.obj", RepoBytes("tests/meshes/assets/prism.obj")}};
}

// The scene as written to disk, loaded from there.
Model SceneFromDisk(const std::string& folder) {
  Folder files(folder);
  for (const auto& [path, bytes] : SceneFiles()) files.Write(path, bytes);
  return LoadXml(files.Write("main.xml", kScene));
}

// Two values are the same, NaN included.
template <typename T>
bool Same(const T& a, const T& b) {
  if constexpr (std::is_floating_point_v<T>) {
    if (std::isnan(a) && std::isnan(b)) return true;
  }
  return a == b;
}

// Every size, array and name of two models agree.
void ExpectSameModel(const Model& a, const Model& b) {
#define SIMLAB_X(size) EXPECT_EQ(a.size, b.size) << #size;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X
#define SIMLAB_X(type, name, rows, cols)                                      \
  EXPECT_EQ(a.name.size(), b.name.size()) << #name;                           \
  for (size_t i = 0; i < a.name.size() && i < b.name.size(); i++) {           \
    if (!Same(a.name[i], b.name[i])) {                                        \
      ADD_FAILURE() << #name "[" << i << "]: " << a.name[i] << " vs " << b.name[i]; \
      break;                                                                  \
    }                                                                         \
  }
  SIMLAB_MODEL_FIELDS(SIMLAB_X)
#undef SIMLAB_X
#define SIMLAB_X(kind, count) EXPECT_EQ(a.kind##_names, b.kind##_names) << #kind;
  SIMLAB_MODEL_NAMED(SIMLAB_X)
#undef SIMLAB_X
}

// The message of the Error a load from memory throws ("" if it loads).
std::string MemoryLoadError(const std::string& xml, const Assets& assets) {
  try {
    LoadXmlString(xml, kMemoryFile, assets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// `msg` contains every one of `parts`.
void ExpectParts(const std::string& msg, const std::vector<std::string>& parts) {
  ASSERT_FALSE(msg.empty()) << "expected an error";
  for (const std::string& part : parts) {
    EXPECT_NE(msg.find(part), std::string::npos) << "missing '" << part << "' in: " << msg;
  }
}

// ---------------------------------------------------------------- loading from memory

TEST(Assets, SceneFromMemoryEqualsSceneFromDisk) {
  Model disk = SceneFromDisk("assets_scene_disk");

  // The assets named by their bare file names, as Python users usually write them.
  Assets assets;
  for (const auto& [path, bytes] : SceneFiles()) assets[fs::path(path).filename().string()] = bytes;
  Model memory = LoadXmlString(kScene, kMemoryFile, assets);
  ExpectSameModel(memory, disk);

  // What came in: the floor, the gripper (its fingers, tendon, actuator, keyframe), the
  // meshes (box: 8 merged vertices; the prism scaled along x).
  EXPECT_EQ(memory.nq, 1 + 2 + 7);
  EXPECT_GE(NameToId(memory, kObjGeom, "floor"), 0);
  EXPECT_GE(NameToId(memory, kObjJoint, "gripper/finger_left"), 0);
  EXPECT_EQ(memory.ntendon, 1);
  EXPECT_EQ(memory.nu, 1);
  EXPECT_EQ(memory.nmesh, 2);
  EXPECT_EQ(memory.mesh_vertnum[0], 8);
  EXPECT_EQ(memory.mesh_vert, disk.mesh_vert);
  EXPECT_EQ(memory.body_mass, disk.body_mass);
  EXPECT_GT(memory.body_mass[NameToId(memory, kObjBody, "carriage")], 0);
}

TEST(Assets, FoldersAndCaseOfAssetNamesDoNotMatter) {
  // MuJoCo keys assets by their base name in lower case, and finds a file by its own.
  Model disk = SceneFromDisk("assets_names_disk");
  std::vector<std::pair<std::string, std::string>> files = SceneFiles();
  Assets assets = {{"elsewhere/FLOOR.XML", files[0].second},
                   {"models/hand.xml", files[1].second},
                   {"/abs/meshes/Box.STL", files[2].second},
                   {"shape.OBJ", files[3].second}};
  ExpectSameModel(LoadXmlString(kScene, kMemoryFile, assets), disk);
}

TEST(Assets, NestedIncludesAndModelsFindTheirFilesToo) {
  // An included file includes another; the attached model includes its defaults. Every
  // file, whichever file names it, comes from the assets.
  std::string hand = RepoBytes("models/gripper.xml");
  size_t defaults = hand.find("  <default>");
  size_t end = hand.find("</default>\n  </default>\n") + std::strlen("</default>\n  </default>\n");
  ASSERT_NE(defaults, std::string::npos);
  std::string hand_defaults = "<mujoco>\n" + hand.substr(defaults, end - defaults) + "</mujoco>\n";
  hand.replace(defaults, end - defaults, "  <include file=\"hand_defaults.xml\"/>\n");
  Assets assets = {
      {"floor.xml", "<mujoco>\n  <include file=\"floor_geom.xml\"/>\n</mujoco>\n"},
      {"floor_geom.xml", kFloor},
      {"hand.xml", hand},
      {"hand_defaults.xml", hand_defaults},
      {"box.stl", RepoBytes("tests/meshes/assets/box.stl")},
      {"shape.obj", RepoBytes("tests/meshes/assets/prism.obj")}};
  ExpectSameModel(LoadXmlString(kScene, kMemoryFile, assets), SceneFromDisk("assets_nested"));
}

// ---------------------------------------------------------------- assets before the disk

TEST(Assets, AnAssetShadowsTheFileOnDisk) {
  Folder files("assets_shadow");
  files.Write("part.xml", "<mujoco>\n  <geom name=\"from_disk\" size=\"0.1\"/>\n</mujoco>\n");
  files.Write("shape.obj", RepoBytes("tests/meshes/assets/prism.obj"));
  const std::string xml =
      "<mujoco>\n  <asset>\n    <mesh name=\"shape\" file=\"shape.obj\"/>\n  </asset>\n"
      "  <worldbody>\n    <include file=\"part.xml\"/>\n"
      "    <geom name=\"shape\" type=\"mesh\" mesh=\"shape\"/>\n  </worldbody>\n</mujoco>\n";
  std::string main = files.Write("main.xml", xml);
  Model disk = LoadXml(main);
  ASSERT_GE(NameToId(disk, kObjGeom, "from_disk"), 0);

  // Both files given: neither is read from disk (the same as with no disk at all).
  Assets assets = {{"part.xml", "<mujoco>\n  <geom name=\"from_asset\" size=\"0.1\"/>\n</mujoco>\n"},
                   {"shape.obj", RepoBytes("tests/meshes/assets/lshape.obj")}};
  Model shadowed = LoadXmlString(xml, main, assets);
  EXPECT_GE(NameToId(shadowed, kObjGeom, "from_asset"), 0);
  EXPECT_EQ(NameToId(shadowed, kObjGeom, "from_disk"), -1);
  EXPECT_NE(shadowed.mesh_vert, disk.mesh_vert);
  ExpectSameModel(shadowed, LoadXmlString(xml, kMemoryFile, assets));

  // Only the include given: the mesh still comes from disk.
  assets.erase("shape.obj");
  Model mixed = LoadXmlString(xml, main, assets);
  EXPECT_GE(NameToId(mixed, kObjGeom, "from_asset"), 0);
  EXPECT_EQ(mixed.mesh_vert, disk.mesh_vert);
}

TEST(Assets, ThreadsLoadWithTheirOwnAssets) {
  // No state is shared between loads: each thread sees only its own assets.
  const std::string xml = "<mujoco>\n  <worldbody>\n    <include file=\"part.xml\"/>\n"
                          "  </worldbody>\n</mujoco>\n";
  std::vector<std::string> found(4);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < found.size(); t++) {
    threads.emplace_back([&, t] {
      std::string name = "geom" + std::to_string(t);
      Assets assets = {{"part.xml", "<mujoco><geom name=\"" + name + "\" size=\"1\"/></mujoco>"}};
      try {
        for (int i = 0; i < 20; i++) {
          found[t] = LoadXmlString(xml, kMemoryFile, assets).geom_names.at(0);
          if (found[t] != name) break;
        }
      } catch (const std::exception& e) {
        found[t] = e.what();
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (size_t t = 0; t < found.size(); t++) EXPECT_EQ(found[t], "geom" + std::to_string(t));
}

// ---------------------------------------------------------------- errors

TEST(Assets, AMissingFileNamesTheElementAndTheAssets) {
  Assets assets = {{"floor.xml", kFloor}};
  const std::string head = "<mujoco>\n  <compiler meshdir=\"meshes\"/>\n";
  ExpectParts(MemoryLoadError(head + "  <include file=\"parts/nowhere.xml\"/>\n</mujoco>\n", assets),
              {"simlab_in_memory_only/main.xml:3:", "cannot open included file 'parts/nowhere.xml'",
               "no asset has that file name"});
  ExpectParts(MemoryLoadError(head + "  <asset>\n    <model file=\"nowhere.xml\"/>\n"
                                     "  </asset>\n</mujoco>\n", assets),
              {"main.xml:4:", "cannot open model file 'simlab_in_memory_only/nowhere.xml'",
               "no asset has that file name"});
  ExpectParts(MemoryLoadError(head + "  <asset>\n    <mesh name=\"m\" file=\"nowhere.stl\"/>\n"
                                     "  </asset>\n</mujoco>\n", assets),
              {"main.xml:4:", "<mesh name=\"m\">",
               "cannot open mesh file 'simlab_in_memory_only/meshes/nowhere.stl'",
               "no asset has that file name"});
}

TEST(Assets, ErrorsInAnAssetNameItsPathAndLine) {
  Assets assets = {{"arm.xml", "<mujoco>\n  <geom size=\"0.1\" colour=\"red\"/>\n</mujoco>\n"}};
  ExpectParts(MemoryLoadError("<mujoco>\n  <worldbody>\n    <include file=\"parts/arm.xml\"/>\n"
                              "  </worldbody>\n</mujoco>\n", assets),
              {"simlab_in_memory_only/parts/arm.xml:2:", "unknown attribute 'colour'"});
  assets = {{"broken.xml", "<mujoco>\n  <default>\n</mujoco>\n"}};
  ExpectParts(MemoryLoadError("<mujoco>\n  <include file=\"broken.xml\"/>\n</mujoco>\n", assets),
              {"broken.xml:", "malformed XML"});
}

TEST(Assets, NamesThatCollideAreRefused) {
  // As MuJoCo's Python binding: one file name, whatever the folders and case.
  ExpectParts(MemoryLoadError("<mujoco/>", {{"asset.xml", "a"}, {"path/ASSET.xml", "b"}}),
              {"Repeated file name in assets", "asset.xml", "path/ASSET.xml"});
  ExpectParts(MemoryLoadError("<mujoco/>", {{"folder/", "a"}}), {"asset 'folder/' has no file name"});
}

}  // namespace
}  // namespace simlab
