// Particle exports through the `sluice` program (io/export.h): VTK XML PolyData of the
// fluid and of the boundary samples, and the ParaView collection (.pvd), from `simulate`
// and `render`; the files are parsed with expat (a real XML parser), their point counts,
// arrays and object ids checked against the scene, the collection's times against the
// frame times, also after an unstable end; --overwrite removes old exports.
#include <expat.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "test_process.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using test::CaseDir;
using test::read_text;
using test::Result;
using test::run_sluice;
using test::write_text;

// An XML element with its attributes, text and children.
struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<Element>> children;

  const Element* child(const std::string& n) const {
    for (const auto& c : children)
      if (c->name == n) return c.get();
    return nullptr;
  }
  std::vector<const Element*> all(const std::string& n) const {
    std::vector<const Element*> out;
    for (const auto& c : children)
      if (c->name == n) out.push_back(c.get());
    return out;
  }
  std::string attribute(const std::string& n) const {
    const auto it = attributes.find(n);
    return it == attributes.end() ? "" : it->second;
  }
};

// Parses `text` with expat; `error` gets expat's message and line when it is not
// well-formed XML.
std::unique_ptr<Element> parse_xml(const std::string& text, std::string& error) {
  struct State {
    std::unique_ptr<Element> root;
    std::vector<Element*> open;
  } state;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &state);
  XML_SetElementHandler(
      parser,
      [](void* data, const XML_Char* name, const XML_Char** attrs) {
        auto* s = static_cast<State*>(data);
        auto e = std::make_unique<Element>();
        e->name = name;
        for (int k = 0; attrs[k]; k += 2) e->attributes[attrs[k]] = attrs[k + 1];
        Element* raw = e.get();
        if (s->open.empty())
          s->root = std::move(e);
        else
          s->open.back()->children.push_back(std::move(e));
        s->open.push_back(raw);
      },
      [](void* data, const XML_Char*) { static_cast<State*>(data)->open.pop_back(); });
  XML_SetCharacterDataHandler(parser, [](void* data, const XML_Char* s, int len) {
    auto* st = static_cast<State*>(data);
    if (!st->open.empty()) st->open.back()->text.append(s, static_cast<size_t>(len));
  });
  if (XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_ERROR) {
    error = std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " +
            std::to_string(XML_GetCurrentLineNumber(parser));
    state.root.reset();
  }
  XML_ParserFree(parser);
  return std::move(state.root);
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> v;
  std::istringstream in(text);
  for (double d; in >> d;) v.push_back(d);
  return v;
}

// One VTK PolyData file: its point count, its point arrays by name (all components, in
// order), its points and its TimeValue.
struct PolyData {
  long points = -1;
  std::map<std::string, std::vector<double>> arrays;
  std::map<std::string, std::string> types;
  std::vector<double> xyz;
  double time = -1;
};

PolyData read_vtp(const fs::path& file) {
  std::string error;
  const auto root = parse_xml(read_text(file), error);
  PolyData d;
  if (!root) {
    ADD_FAILURE() << file << " is not well-formed XML: " << error;
    return d;
  }
  EXPECT_EQ(root->name, "VTKFile");
  EXPECT_EQ(root->attribute("type"), "PolyData");
  const Element* poly = root->child("PolyData");
  if (!poly || !poly->child("Piece")) {
    ADD_FAILURE() << file << ": no PolyData/Piece";
    return d;
  }
  if (const Element* field = poly->child("FieldData"))
    for (const Element* a : field->all("DataArray"))
      if (a->attribute("Name") == "TimeValue") d.time = numbers(a->text).at(0);
  const Element* piece = poly->child("Piece");
  d.points = std::stol(piece->attribute("NumberOfPoints"));
  EXPECT_EQ(piece->attribute("NumberOfVerts"), piece->attribute("NumberOfPoints")) << file;
  for (const Element* a : piece->child("PointData")->all("DataArray")) {
    d.arrays[a->attribute("Name")] = numbers(a->text);
    d.types[a->attribute("Name")] = a->attribute("type");
  }
  d.xyz = numbers(piece->child("Points")->child("DataArray")->text);
  const auto cells = piece->child("Verts")->all("DataArray");
  EXPECT_EQ(cells.size(), 2u) << file << ": Verts needs connectivity and offsets";
  for (const Element* c : cells) EXPECT_EQ(numbers(c->text).size(), static_cast<size_t>(d.points)) << file;
  return d;
}

// The collection's (timestep, part, file) entries.
struct DataSet {
  double time;
  std::string part, file;
};

std::vector<DataSet> read_pvd(const fs::path& file) {
  std::string error;
  const auto root = parse_xml(read_text(file), error);
  std::vector<DataSet> out;
  if (!root) {
    ADD_FAILURE() << file << " is not well-formed XML: " << error;
    return out;
  }
  EXPECT_EQ(root->attribute("type"), "Collection");
  for (const Element* d : root->child("Collection")->all("DataSet"))
    out.push_back({std::stod(d->attribute("timestep")), d->attribute("part"), d->attribute("file")});
  return out;
}

// A tank, a circle at rest and a paddle swinging into the fluid: three objects, the
// last one moving. 20 frames per second for 0.1 s.
const char* kScene = R"({
  "name": "exp", "spacing": 0.05,
  "time": {"duration": 0.1, "fps": 20, "dt": 0.005},
  "output": {"export": ["vtk"]},
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 0.3]}],
  "boundaries": [
    {"name": "tank", "shape": "box", "min": [0, 0], "max": [1, 0.6]},
    {"name": "stone", "shape": "circle", "center": [0.7, 0.1], "radius": 0.08},
    {"name": "paddle", "shape": "polygon", "points": [[0.85, 0.05], [0.9, 0.05], [0.9, 0.4], [0.85, 0.4]],
     "motion": {"type": "oscillation", "angular_amplitude": 0.3, "pivot": [0.875, 0.05], "period": 0.5}}
  ]
})";

constexpr int kFrames = 3;  // frames 0, 1, 2 at 0, 0.05, 0.1 s

// The exports of a finished run in `particles`: every frame's files, counts, arrays
// and object ids as in the scene, and the collection at the frame times.
void expect_exports(const fs::path& particles, const Scene& scene, int frames) {
  const std::vector<DataSet> sets = read_pvd(particles / "particles.pvd");
  ASSERT_EQ(sets.size(), static_cast<size_t>(2 * frames)) << "a fluid and a boundary part per frame";
  for (int k = 0; k < frames; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame_%05d", k);
    const double t = std::min(k / scene.time.fps, scene.time.duration);
    EXPECT_EQ(sets[2 * k].time, t);
    EXPECT_EQ(sets[2 * k + 1].time, t);
    EXPECT_EQ(sets[2 * k].part, "0");
    EXPECT_EQ(sets[2 * k + 1].part, "1");
    EXPECT_EQ(sets[2 * k].file, std::string(stem) + "_fluid.vtp");
    EXPECT_EQ(sets[2 * k + 1].file, std::string(stem) + "_boundary.vtp");

    PolyData fluid = read_vtp(particles / sets[2 * k].file);
    const long nf = static_cast<long>(scene.fluid_x.size());
    EXPECT_EQ(fluid.points, nf);
    EXPECT_EQ(fluid.time, t);
    EXPECT_EQ(fluid.xyz.size(), static_cast<size_t>(3 * nf));
    EXPECT_EQ(fluid.arrays["velocity"].size(), static_cast<size_t>(3 * nf));
    for (const char* name : {"pressure", "density", "id"})
      EXPECT_EQ(fluid.arrays[name].size(), static_cast<size_t>(nf)) << name;
    EXPECT_EQ(fluid.types["id"], "Int32");
    for (long i = 0; i < nf; ++i) EXPECT_EQ(fluid.arrays["id"][i], i) << "fluid in the scene's initial order";

    PolyData wall = read_vtp(particles / sets[2 * k + 1].file);
    const long nb = static_cast<long>(scene.boundary_x.size());
    EXPECT_EQ(wall.points, nb);
    EXPECT_EQ(wall.arrays["velocity"].size(), static_cast<size_t>(3 * nb));
    for (const char* name : {"object_id", "pressure", "volume"})
      EXPECT_EQ(wall.arrays[name].size(), static_cast<size_t>(nb)) << name;
    EXPECT_EQ(wall.types["object_id"], "Int32");
    // Each object's samples carry its index; only the paddle's move (after t = 0).
    std::vector<long> per_object(scene.objects.size(), 0);
    for (long i = 0; i < nb; ++i) {
      const auto object = static_cast<size_t>(wall.arrays["object_id"][i]);
      ASSERT_LT(object, scene.objects.size());
      ++per_object[object];
      const double speed = std::hypot(wall.arrays["velocity"][3 * i], wall.arrays["velocity"][3 * i + 1]);
      if (!scene.objects[object].moving) {
        EXPECT_EQ(speed, 0.0) << "sample " << i << " of " << scene.objects[object].name;
      } else if (k > 0) {
        EXPECT_GT(speed, 0.0) << "sample " << i << " of the paddle";
      }
    }
    for (size_t o = 0; o < scene.objects.size(); ++o)
      EXPECT_EQ(per_object[o], scene.objects[o].count) << scene.objects[o].name;
  }
}

TEST(Exports, SimulateWritesVtpFilesAndTheCollection) {
  CaseDir dir;
  write_text(dir.work() / "x.json", kScene);
  const Scene scene = load_scene((dir.work() / "x.json").string());
  ASSERT_EQ(scene.objects.size(), 3u);
  ASSERT_TRUE(scene.objects[2].moving);
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--export", "csv,vtk"});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_exports(dir.work() / "out/particles", scene, kFrames);
  for (int k = 0; k < kFrames; ++k)
    EXPECT_TRUE(fs::exists(dir.work() / ("out/particles/frame_0000" + std::to_string(k) + ".csv")));
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["parameters"]["output"]["export"], nlohmann::json({"csv", "vtk"}))
      << "--export replaces output.export";
}

// An unstable run keeps a collection that lists exactly the frames whose files exist.
TEST(Exports, CollectionIsValidAfterAnUnstableRun) {
  CaseDir dir;
  write_text(dir.work() / "x.json", kScene);
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--set", "fluid.0.velocity=[0, 40]",
                                    "--set", "stability.bounds_margin=0.05", "--set", "time.duration=1"});
  ASSERT_EQ(r.status, 4) << r.err;
  const std::vector<DataSet> sets = read_pvd(dir.work() / "out/particles/particles.pvd");
  ASSERT_GE(sets.size(), 2u);
  ASSERT_LT(sets.size(), 40u) << "the run should stop well before its end";
  for (const DataSet& d : sets) EXPECT_TRUE(fs::exists(dir.work() / "out/particles" / d.file)) << d.file;
  for (const auto& e : fs::directory_iterator(dir.work() / "out/particles"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// --overwrite removes the exports of the previous run (and nothing else in particles/).
TEST(Exports, OverwriteRemovesOldExports) {
  CaseDir dir;
  write_text(dir.work() / "x.json", kScene);
  ASSERT_EQ(run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--export", "csv,vtk"}).status, 0);
  write_text(dir.work() / "out/particles/frame_00009.vtk", "an older version's legacy file");
  write_text(dir.work() / "out/particles/notes.txt", "mine");
  const Result r =
      run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--overwrite", "--set", "output.export=[]"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir.work() / "out/particles"))
    left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"notes.txt"});
}

// `render` writes the scene's output.export, and --export replaces it. Needs EGL (Render*).
TEST(RenderExports, RenderWritesTheScenesExportsAndTheFlags) {
  CaseDir dir;
  write_text(dir.work() / "x.json", kScene);
  const Scene scene = load_scene((dir.work() / "x.json").string());
  Result r = run_sluice(dir, {"render", "x.json", "-q", "-o", "a", "--no-video", "--resolution", "64x36"});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_exports(dir.work() / "a/particles", scene, kFrames);
  EXPECT_FALSE(fs::exists(dir.work() / "a/particles/frame_00000.csv"));
  EXPECT_TRUE(fs::exists(dir.work() / "a/frames/frame_00002.png"));

  r = run_sluice(dir, {"render", "x.json", "-q", "-o", "b", "--no-video", "--resolution", "64x36", "--export", "csv"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.work() / "b/particles/frame_00002.csv"));
  EXPECT_FALSE(fs::exists(dir.work() / "b/particles/particles.pvd"));
  // The same files as `simulate` writes: the same state through the same writer.
  ASSERT_EQ(run_sluice(dir, {"simulate", "x.json", "-q", "-o", "s"}).status, 0);
  for (const char* f : {"frame_00002_fluid.vtp", "frame_00002_boundary.vtp", "particles.pvd"})
    EXPECT_EQ(read_text(dir.work() / "a/particles" / f), read_text(dir.work() / "s/particles" / f)) << f;

  r = run_sluice(dir, {"render", "x.json", "-q", "-o", "c", "--export", "vtk,png"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--export: png not in {csv,vtk}"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.work() / "c"));
}

}  // namespace
}  // namespace sluice
