// Replacing or appending a marked section of a text file.
#include "util/marked_section.h"

namespace gv {

std::string replaceMarkedSection(const std::string& text, const std::string& begin,
                                 const std::string& end, const std::string& body) {
  std::string content = body;
  if (content.empty() || content.back() != '\n') content += '\n';
  const size_t b = text.find(begin);
  const size_t e = b == std::string::npos ? std::string::npos : text.find(end, b + begin.size());
  if (e == std::string::npos) {
    std::string out = text;
    if (!out.empty() && out.back() != '\n') out += '\n';
    if (!out.empty()) out += '\n';
    return out + begin + "\n" + content + end + "\n";
  }
  // Keep the begin marker's whole line and everything from the end marker's line on.
  size_t afterBegin = text.find('\n', b);
  afterBegin = afterBegin == std::string::npos ? text.size() : afterBegin + 1;
  const size_t lineStart = text.rfind('\n', e);
  const size_t endLine = lineStart == std::string::npos ? 0 : lineStart + 1;
  if (endLine < afterBegin) {  // both markers on one line: the body goes between two lines
    return text.substr(0, b) + begin + "\n" + content + text.substr(e);
  }
  return text.substr(0, afterBegin) + content + text.substr(endLine);
}

}  // namespace gv
