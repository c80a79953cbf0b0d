#include "swarm_transport/ros/engine/batch_files.h"

#include <cmath>
#include <cstdio>

namespace swarm_transport {

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  std::string text = buffer;
  // A float stays a float for the reader (Python's json: 0.0, not 0).
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

std::string JsonObject::Text(const std::string& indent) const {
  std::string out = "{";
  for (std::size_t i = 0; i < members_.size(); ++i) {
    out += i == 0 ? "\n" : ",\n";
    out += indent + " " + JsonString(members_[i].first) + ": " + members_[i].second;
  }
  return out + (members_.empty() ? "}" : "\n" + indent + "}");
}

}  // namespace swarm_transport
