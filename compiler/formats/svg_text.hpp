// Small pieces of SVG text shared by the plots: escaping, short numbers, elements.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace seqc::compiler::svg {

// Text for an XML 1.0 (and HTML) document, in element text or a double-quoted attribute: & < >
// and " as entities, and what XML 1.0 cannot hold at all (C0 controls other than tab, newline
// and carriage return; U+FFFE, U+FFFF; bytes that are not UTF-8) as U+FFFD, so a name holding
// any byte still gives a well-formed file. ' is copied: no attribute here is single-quoted.
std::string escape(std::string_view text);
std::string num(double v);  // at most two decimals, no trailing zeros
std::string text(double x, double y, std::string_view body, std::string_view attrs = "");
std::string line(double x1, double y1, double x2, double y2, std::string_view attrs);
std::string rect(double x, double y, double w, double h, std::string_view attrs);
// A polyline through the points; several runs when NaN values (unknown) cut it.
std::string polylines(const std::vector<double>& xs, const std::vector<double>& ys,
                      std::string_view attrs);
// A "nice" step for axis ticks: 1, 2 or 5 times a power of ten, about span / target.
double nice_step(double span, int target);
std::string document(double width, double height, const std::string& title,
                     const std::string& body);

}  // namespace seqc::compiler::svg
