#include "compiler/formats/svg_text.hpp"

#include <cmath>
#include <cstdio>

namespace seqc::compiler::svg {

std::string escape(std::string_view text) {
  std::string out;
  for (char c : text) {
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
        out += c;
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
