// Rewriting one generated section of a text file (a markdown page's benchmark table) between two
// marker lines, leaving the rest as it is.
#pragma once

#include <string>

namespace gv {

/// `text` with everything between the line holding `begin` and the line holding `end` (markers
/// kept) replaced by `body`; when the markers are missing (or `end` does not follow `begin`), the
/// markers and body are appended at the end, after a blank line. `body` gets a final newline if
/// it lacks one.
std::string replaceMarkedSection(const std::string& text, const std::string& begin,
                                 const std::string& end, const std::string& body);

}  // namespace gv
