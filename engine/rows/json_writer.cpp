#include "engine/rows/json_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "engine/rows/result_columns.hpp"

namespace chaosweep {

std::string json_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out;
}

std::string row_to_json(const RunRow& row, bool pretty) {
  std::string out = "{";
  bool first = true;
  for (const Column& c : result_columns()) {
    out += first ? "" : ",";
    out += pretty ? "\n  " : "";
    first = false;
    out += '"';
    out += c.name;
    out += pretty ? "\": " : "\":";
    const CellValue v = c.get(row);
    if (const double* d = std::get_if<double>(&v)) {
      if (std::isfinite(*d)) {
        char buf[32];  // shortest text that reads back to the same double
        const auto res = std::to_chars(buf, buf + sizeof buf, *d);
        out.append(buf, res.ptr);
      } else {
        out += "null";
      }
    } else if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) {
      out += std::to_string(*i);
    } else {
      out += '"';
      out += json_escape(std::get<std::string>(v));
      out += '"';
    }
  }
  out += pretty ? "\n}" : "}";
  return out;
}

}  // namespace chaosweep
