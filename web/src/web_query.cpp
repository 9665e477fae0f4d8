#include "web_query.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace polarview {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(separator, start);
    if (end == std::string::npos) end = text.size();
    parts.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

}  // namespace

std::string percentDecode(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '+') {
      out += ' ';
    } else if (text[i] == '%' && i + 2 < text.size() + 0 && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
               std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out += static_cast<char>(std::strtol(text.substr(i + 1, 2).c_str(), nullptr, 16));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::string percentEncode(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == ',') {
      out += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

WebSettings parseWebQuery(const std::string& query, std::vector<std::string>* errors) {
  WebSettings settings;
  auto fail = [&](const std::string& message) {
    if (errors) errors->push_back(message);
  };
  const std::string text = !query.empty() && query[0] == '?' ? query.substr(1) : query;
  if (text.empty()) return settings;
  for (const std::string& pair : split(text, '&')) {
    if (pair.empty()) continue;
    const size_t eq = pair.find('=');
    const std::string key = percentDecode(pair.substr(0, eq));
    const std::string value = eq == std::string::npos ? std::string() : percentDecode(pair.substr(eq + 1));
    if (key == "scheme" || key == "schemes") {
      // One view per name, at most kMaxWebViews.
      std::vector<SchemeChoice> schemes;
      for (const std::string& name : split(value, ',')) {
        if (std::optional<SchemeChoice> scheme = parseSchemeChoice(name)) schemes.push_back(*scheme);
        else fail("scheme '" + name + "' unknown (one of " + schemeChoiceNames(", ") + ")");
      }
      if (schemes.size() > size_t(kMaxWebViews)) {
        fail("at most " + std::to_string(kMaxWebViews) + " views: the first ones are shown");
        schemes.resize(size_t(kMaxWebViews));
      }
      if (!schemes.empty()) settings.schemes = schemes;
    } else if (key == "level") {
      char* end = nullptr;
      const long level = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || level < 0 || level > kMaxLevel)
        fail("level '" + value + "' is not a level 0.." + std::to_string(kMaxLevel));
      else settings.level = int(level);
    } else if (key == "shade") {
      if (std::optional<ShadingParams::Mode> mode = parseShadeMode(value)) settings.shade = *mode;
      else fail("shade '" + value + "' unknown (shaded, gaussian, mean, highlight, reflection)");
    } else if (key == "camera") {
      std::string error;
      if (std::optional<OrbitCamera> camera = cameraFromJson(value, OrbitCamera{}, &error)) settings.camera = camera;
      else fail("camera: " + error);
    } else if (key == "panels") {
      settings.panels = !(value == "0" || value == "false" || value == "off");
    }
  }
  return settings;
}

std::string makeWebQuery(const WebSettings& settings, const OrbitCamera& camera) {
  std::string schemes;
  for (SchemeChoice scheme : settings.schemes) schemes += (schemes.empty() ? "" : ",") + std::string(schemeChoiceCliName(scheme));
  std::string query = "?scheme=" + schemes + "&level=" + std::to_string(settings.level) +
                      "&shade=" + shadeModeName(settings.shade) + "&camera=" + percentEncode(cameraToJson(camera));
  if (!settings.panels) query += "&panels=0";
  return query;
}

}  // namespace polarview
