// The list of scene generators, for the CLI's `globalvis gen NAME`.
#pragma once

#include <string>
#include <vector>

namespace gv {

/// A generator the CLI can run: `name` is the command-line word, `description` one line for help.
/// The options of each are the fields of its options struct (CornellBoxOptions, OfficeOptions,
/// MazeOptions, FurnishedRoomOptions), documented in its header.
struct GeneratorInfo {
  std::string name, description;
};

/// Every generator, in the order to list them.
inline const std::vector<GeneratorInfo>& generatorList() {
  static const std::vector<GeneratorInfo> list{
      {"cornell",
       "the Cornell box, published geometry in mm, 19 patches (generators/cornell_box.h)"},
      {"office",
       "floors x rows x columns office rooms with doors, windows, furniture and lights; "
       "default 406 patches (generators/office.h)"},
      {"maze",
       "a random perfect maze of thin walls with floor, ceiling and lights "
       "(generators/maze.h)"},
      {"room",
       "a furnished room (table, chairs, bookcase, two ceiling lights), the kind of "
       "scene HSA91 and SPLASH-2 RADIOSITY test on; 224 patches "
       "(generators/furnished_room.h)"},
  };
  return list;
}

}  // namespace gv
