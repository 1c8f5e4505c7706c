// `globalvis gen NAME [options] -o FILE.obj`: the built-in scenes (Cornell box, office, maze,
// furnished room).
#include <fmt/core.h>

#include <chrono>
#include <memory>

#include "cli/commands.h"
#include "generators/cornell_box.h"
#include "generators/furnished_room.h"
#include "generators/generators.h"
#include "generators/maze.h"
#include "generators/office.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "util/timing.h"

namespace gv::cli {
namespace {

struct GenState {
  std::string output;
  CornellBoxOptions cornell;
  OfficeOptions office;
  size_t officePatches = 0;  ///< 0: use floors/rows/columns as given
  MazeOptions maze;
  FurnishedRoomOptions room;
};

void addOutputOption(CLI::App* cmd, GenState& s) {
  cmd->add_option("-o,--output", s.output, "Output OBJ file (its .mtl is written beside it)")
      ->required();
}

const std::string& describe(const std::string& name) {
  for (const GeneratorInfo& g : generatorList())
    if (g.name == name) return g.description;
  static const std::string none;
  return none;
}

}  // namespace

Action addGenCommand(CLI::App& app) {
  auto* gen = app.add_subcommand(
      "gen", "Generate a built-in scene (cornell, office, maze, room) as OBJ+MTL");
  gen->require_subcommand(1);
  auto s = std::make_shared<GenState>();

  auto* cornell = gen->add_subcommand("cornell", describe("cornell"));
  addOutputOption(cornell, *s);
  cornell->add_flag("--closed", s->cornell.closedFront, "Close the open front with a white wall");

  auto* office = gen->add_subcommand("office", describe("office"));
  addOutputOption(office, *s);
  OfficeOptions& o = s->office;
  auto* patches = office
                      ->add_option("--patches", s->officePatches,
                                   "Choose floors/rows/columns to get about this many patches")
                      ->check(CLI::Range(size_t{1}, size_t{100'000'000}));
  office->add_option("--floors", o.floors, "Storeys")
      ->check(CLI::Range(1, 10000))
      ->excludes(patches);
  office->add_option("--rows", o.rows, "Rows of rooms, each with its corridor")
      ->check(CLI::Range(1, 10000))
      ->excludes(patches);
  office->add_option("--columns", o.columns, "Rooms per row")
      ->check(CLI::Range(1, 10000))
      ->excludes(patches);
  office->add_option("--seed", o.seed, "Seed for door positions and furniture");
  office->add_option("--furniture-per-room", o.furniturePerRoom, "Furniture boxes per room")
      ->check(CLI::Range(0, 100));
  office->add_flag("!--no-doors", o.doors, "Seal every room (no doors)");
  office->add_flag("!--no-windows", o.windows, "No interior windows between rooms");
  office->add_flag("!--no-furniture", o.furniture, "No furniture");
  office->add_flag("!--no-lights", o.lights, "No ceiling lights");
  office->add_option("--light-emission", o.lightEmission, "Emitted radiosity of the lights")
      ->check(CLI::NonNegativeNumber);

  auto* maze = gen->add_subcommand("maze", describe("maze"));
  addOutputOption(maze, *s);
  maze->add_option("--width", s->maze.width, "Cells along x")->check(CLI::Range(1, 100000));
  maze->add_option("--height", s->maze.height, "Cells along y")->check(CLI::Range(1, 100000));
  maze->add_option("--seed", s->maze.seed, "Seed of the maze and the lights");
  maze->add_option("--lights", s->maze.lights, "Light panels (0: one per 16 cells)")
      ->check(CLI::Range(0, 1000000));

  auto* room = gen->add_subcommand("room", describe("room"));
  addOutputOption(room, *s);
  room->add_option("--chairs", s->room.chairs, "Chairs around the table")
      ->capture_default_str()
      ->check(CLI::Range(0, 4));
  room->add_flag("!--no-bookcase", s->room.bookcase, "No bookcase");
  room->add_option("--light-emission", s->room.lightEmission, "Emitted radiosity of the lights")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);

  return [s, cornell, office, maze, room]() {
    const auto start = Clock::now();
    Scene scene;
    std::string name;
    try {
      if (cornell->parsed()) {
        name = "cornell";
        scene = generateCornellBox(s->cornell);
      } else if (office->parsed()) {
        name = "office";
        if (s->officePatches > 0) {
          OfficeOptions sized = officeOptionsForPatchCount(s->officePatches);
          s->office.floors = sized.floors;
          s->office.rows = sized.rows;
          s->office.columns = sized.columns;
        }
        scene = generateOffice(s->office);
      } else if (room->parsed()) {
        name = "room";
        scene = generateFurnishedRoom(s->room);
      } else {
        name = "maze";
        scene = generateMaze(s->maze);
      }
    } catch (const std::invalid_argument& e) {
      throw InputError("gen " + name, 0, e.what());
    }
    const double seconds = secondsSince(start);
    writeObj(scene, s->output);
    fmt::print("{}: {} patches, {} emitters, generated in {:.3f} s, written to {}\n", name,
               scene.patches.size(), scene.emitterCount(), seconds, s->output);
    return 0;
  };
}

}  // namespace gv::cli
