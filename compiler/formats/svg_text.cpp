#include "compiler/formats/svg_text.hpp"

#include <cmath>
#include <cstdio>

#include "base/utf8.hpp"

namespace seqc::compiler::svg {
namespace {
constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD
}  // namespace

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = seqc::utf8_length(text, i);
    const std::string_view one = text.substr(i, n == 0 ? 1 : n);
    i += one.size();
    // U+FFFE and U+FFFF (EF BF BE, EF BF BF) are no XML characters either.
    const bool nonchar = n == 3 && c == 0xEF && static_cast<unsigned char>(one[1]) == 0xBF &&
                         static_cast<unsigned char>(one[2]) >= 0xBE;
    if (n == 0 || nonchar || (n == 1 && c < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
      out += kReplacement;
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out.append(one);
    }
  }
  return out;
}

std::string num(double v) {
  if (std::abs(v) < 0.005) v = 0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string text(double x, double y, std::string_view body, std::string_view attrs) {
  return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\"" + (attrs.empty() ? "" : " ") +
         std::string(attrs) + ">" + escape(body) + "</text>\n";
}

std::string line(double x1, double y1, double x2, double y2, std::string_view attrs) {
  return "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" +
         num(y2) + "\" " + std::string(attrs) + "/>\n";
}

std::string rect(double x, double y, double w, double h, std::string_view attrs) {
  return "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" +
         num(h) + "\" " + std::string(attrs) + "/>\n";
}

std::string polylines(const std::vector<double>& xs, const std::vector<double>& ys,
                      std::string_view attrs) {
  std::string out;
  std::string points;
  auto flush = [&] {
    if (!points.empty()) {
      out += "<polyline points=\"" + points + "\" " + std::string(attrs) + "/>\n";
    }
    points.clear();
  };
  for (std::size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
    if (std::isnan(ys[i])) {
      flush();
      continue;
    }
    points += (points.empty() ? "" : " ") + num(xs[i]) + "," + num(ys[i]);
  }
  flush();
  return out;
}

double nice_step(double span, int target) {
  if (span <= 0 || target <= 0) return 1;
  const double raw = span / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10 * power;
}

std::string document(double width, double height, const std::string& title,
                     const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" +
         num(height) + "\" viewBox=\"0 0 " + num(width) + " " + num(height) +
         "\" font-family=\"sans-serif\" font-size=\"11\">\n<title>" + escape(title) + "</title>\n" +
         rect(0, 0, width, height, "fill=\"#ffffff\"") + body + "</svg>\n";
}

}  // namespace seqc::compiler::svg
