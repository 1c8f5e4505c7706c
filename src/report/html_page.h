// Building self-contained HTML pages (no server, no network): escaping, inline data, the viewer.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace gv {

/// Text safe inside HTML elements and attribute values (& < > " ' escaped).
std::string htmlEscape(std::string_view text);

/// JSON text safe inside <script type="application/json">: every `<` is written `\u003c`
/// (it can only occur inside strings), so nothing in it can close the element.
std::string jsonForScript(const nlohmann::json& value);

/// Standard base64 (RFC 4648, with padding), for data: URIs.
std::string base64Encode(std::string_view bytes);

/// The viewer page: `data` (see viewer_data.h) in script#gv-data and the bundled viewer script
/// (build/web/viewer.js) inline. Throws std::invalid_argument if the bundle could close its
/// <script> element.
std::string viewerPageHtml(const std::string& title, std::string_view bundle,
                           const nlohmann::json& data);

}  // namespace gv
