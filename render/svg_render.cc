#include "render/svg_render.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace minenav {

double NiceLength(double approx) {
  const double p = std::pow(10.0, std::floor(std::log10(approx)));
  const double m = approx / p;
  const double nice = m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0;
  return nice * p;
}

namespace {

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

struct Bounds {
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -std::numeric_limits<double>::infinity(), max_y = max_x;
  void Add(const Eigen::Vector2d& p) {
    if (!p.allFinite()) return;
    min_x = std::min(min_x, p.x());
    min_y = std::min(min_y, p.y());
    max_x = std::max(max_x, p.x());
    max_y = std::max(max_y, p.y());
  }
  bool empty() const { return !(max_x >= min_x); }
};

// World metres to SVG pixels.
struct Frame {
  double scale = 1.0;  // px per m
  double x0 = 0.0, y1 = 0.0, margin = 0.0, top = 0.0;
  double X(double x) const { return margin + (x - x0) * scale; }
  double Y(double y) const { return top + (y1 - y) * scale; }
};

class Writer {
 public:
  Writer() { os_ << std::fixed << std::setprecision(1); }
  std::ostringstream& os() { return os_; }
  std::string str() const { return os_.str(); }

 private:
  std::ostringstream os_;
};

// One marker centred on (x, y) px, `r` px from the centre to its edge.
std::string MarkerShape(SvgMarkers::Shape shape, double x, double y, double r) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(1);
  switch (shape) {
    case SvgMarkers::Shape::kCircle:
      os << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"" << r << "\"/>";
      break;
    case SvgMarkers::Shape::kSquare:
      os << "<rect x=\"" << x - r << "\" y=\"" << y - r << "\" width=\"" << 2 * r << "\" height=\"" << 2 * r << "\"/>";
      break;
    case SvgMarkers::Shape::kDiamond:
      os << "<path d=\"M" << x << " " << y - r << "L" << x + r << " " << y << "L" << x << " " << y + r << "L" << x - r
         << " " << y << "Z\"/>";
      break;
    case SvgMarkers::Shape::kCross:
      os << "<path d=\"M" << x - r << " " << y - r << "L" << x + r << " " << y + r << "M" << x - r << " " << y + r << "L"
         << x + r << " " << y - r << "\" stroke-width=\"2.5\"/>";
      break;
  }
  return os.str();
}

}  // namespace

std::string RenderSvg(const SvgScene& scene, const SvgRenderOptions& options) {
  Bounds b;
  for (const auto& l : scene.lines) {
    for (const auto& s : l.segments) {
      b.Add(s.a);
      b.Add(s.b);
    }
    for (const auto& pl : l.polylines)
      for (const auto& p : pl.points) b.Add(p);
  }
  for (const auto& t : scene.trajectories)
    for (const auto& p : t.poses) b.Add(p.translation());
  for (const auto& m : scene.markers)
    for (const auto& p : m.poses) b.Add(p.translation());
  const bool have_lines_or_tracks = !b.empty();
  // Scan points widen the view only when nothing else defines it: a stray long return
  // should not shrink the mine to a corner.
  for (const auto& l : scene.points)
    for (const auto& p : l.points)
      if (!have_lines_or_tracks) b.Add(p);
  if (b.empty()) {
    b.Add({-1.0, -1.0});
    b.Add({1.0, 1.0});
  }
  const double pad = 0.03 * std::max({b.max_x - b.min_x, b.max_y - b.min_y, 1.0});
  b.min_x -= pad;
  b.min_y -= pad;
  b.max_x += pad;
  b.max_y += pad;
  const double span_x = b.max_x - b.min_x, span_y = b.max_y - b.min_y;

  Frame f;
  f.scale = std::min(options.width_px / span_x, options.max_height_px / span_y);
  f.x0 = b.min_x;
  f.y1 = b.max_y;
  f.margin = options.margin_px;
  const double title_h = 28.0 + 18.0 * static_cast<double>(scene.notes.size());
  f.top = options.margin_px + title_h;
  const double draw_w = span_x * f.scale, draw_h = span_y * f.scale;
  const double total_w = draw_w + 2.0 * options.margin_px + options.legend_width_px;
  const double total_h = std::max(draw_h + f.top + options.margin_px + 40.0, f.top + 400.0);

  Writer w;
  auto& os = w.os();
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << total_w << "\" height=\"" << total_h
     << "\" viewBox=\"0 0 " << total_w << " " << total_h << "\" font-family=\"sans-serif\">\n"
     << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  os << "<text x=\"" << options.margin_px << "\" y=\"" << options.margin_px << "\" font-size=\"18\">"
     << Escape(scene.title) << "</text>\n";
  for (size_t i = 0; i < scene.notes.size(); ++i)
    os << "<text x=\"" << options.margin_px << "\" y=\"" << options.margin_px + 22.0 + 18.0 * static_cast<double>(i)
       << "\" font-size=\"13\" fill=\"#444\">" << Escape(scene.notes[i]) << "</text>\n";

  const double bar_m = NiceLength(span_x / 6.0);
  // Grid, clipped to the drawing area.
  os << "<rect x=\"" << f.X(b.min_x) << "\" y=\"" << f.Y(b.max_y) << "\" width=\"" << draw_w << "\" height=\""
     << draw_h << "\" fill=\"none\" stroke=\"#bbb\" stroke-width=\"1\"/>\n";
  if (options.grid) {
    os << "<g stroke=\"#eee\" stroke-width=\"1\">\n";
    for (double x = std::ceil(b.min_x / bar_m) * bar_m; x <= b.max_x; x += bar_m)
      os << "<line x1=\"" << f.X(x) << "\" y1=\"" << f.Y(b.min_y) << "\" x2=\"" << f.X(x) << "\" y2=\""
         << f.Y(b.max_y) << "\"/>\n";
    for (double y = std::ceil(b.min_y / bar_m) * bar_m; y <= b.max_y; y += bar_m)
      os << "<line x1=\"" << f.X(b.min_x) << "\" y1=\"" << f.Y(y) << "\" x2=\"" << f.X(b.max_x) << "\" y2=\""
         << f.Y(y) << "\"/>\n";
    os << "</g>\n";
  }

  // Everything in world coordinates is clipped to the drawing area, so stray points (a
  // scan at a bad pose) never run over the legend.
  os << "<clipPath id=\"area\"><rect x=\"" << f.X(b.min_x) << "\" y=\"" << f.Y(b.max_y) << "\" width=\"" << draw_w
     << "\" height=\"" << draw_h << "\"/></clipPath>\n<g clip-path=\"url(#area)\">\n";
  for (const auto& a : scene.areas) {
    if (a.polygons.empty()) continue;
    os << "<path stroke=\"none\" fill=\"" << a.color << "\" fill-opacity=\"" << a.opacity << "\" d=\"";
    for (const auto& poly : a.polygons)
      for (size_t i = 0; i < poly.size(); ++i)
        os << (i ? "L" : "M") << f.X(poly[i].x()) << " " << f.Y(poly[i].y()) << (i + 1 == poly.size() ? "Z" : "");
    os << "\"/>\n";
  }
  // Dots as zero-length round-capped strokes: a fraction of the size of one <circle>
  // per point, so a 42-scan survey stays a few megabytes.
  for (const auto& l : scene.points) {
    if (l.points.empty()) continue;
    os << "<path stroke=\"" << l.color << "\" stroke-opacity=\"" << l.opacity << "\" stroke-width=\""
       << 2.0 * l.radius_px << "\" stroke-linecap=\"round\" fill=\"none\" d=\"";
    for (const auto& p : l.points) {
      if (!p.allFinite()) continue;
      os << "M" << f.X(p.x()) << " " << f.Y(p.y()) << "h0";
    }
    os << "\"/>\n";
  }

  for (const auto& l : scene.lines) {
    os << "<g stroke=\"" << l.color << "\" stroke-width=\"" << l.width_px
       << "\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    if (!l.segments.empty()) {
      os << "<path d=\"";
      for (const auto& s : l.segments)
        os << "M" << f.X(s.a.x()) << " " << f.Y(s.a.y()) << "L" << f.X(s.b.x()) << " " << f.Y(s.b.y());
      os << "\"/>\n";
    }
    for (const auto& pl : l.polylines) {
      if (pl.points.empty()) continue;
      os << "<path d=\"";
      for (size_t i = 0; i < pl.points.size(); ++i)
        os << (i ? "L" : "M") << f.X(pl.points[i].x()) << " " << f.Y(pl.points[i].y());
      if (pl.closed) os << "Z";
      os << "\"/>\n";
    }
    os << "</g>\n";
  }

  for (const auto& l : scene.links) {
    if (l.links.empty()) continue;
    os << "<path stroke=\"" << l.color << "\" stroke-width=\"1\" fill=\"none\" d=\"";
    for (const auto& [a, c] : l.links) os << "M" << f.X(a.x()) << " " << f.Y(a.y()) << "L" << f.X(c.x()) << " " << f.Y(c.y());
    os << "\"/>\n";
  }

  const double tick_m = 12.0 / f.scale;  // heading tick: 12 px at any scale
  for (const auto& t : scene.trajectories) {
    if (t.poses.empty()) continue;
    os << "<g stroke=\"" << t.color << "\" fill=\"none\" stroke-width=\"" << t.width_px << "\""
       << (t.dashed ? " stroke-dasharray=\"6 4\"" : "") << ">\n<path d=\"";
    for (size_t i = 0; i < t.poses.size(); ++i)
      os << (i ? "L" : "M") << f.X(t.poses[i].x) << " " << f.Y(t.poses[i].y);
    os << "\"/>\n</g>\n";
    if (t.markers) {
      os << "<g stroke=\"" << t.color << "\" fill=\"white\" stroke-width=\"1.5\">\n";
      for (const auto& p : t.poses) {
        const Eigen::Vector2d tip = p * Eigen::Vector2d(tick_m, 0.0);
        os << "<circle cx=\"" << f.X(p.x) << "\" cy=\"" << f.Y(p.y) << "\" r=\"3.5\"/>"
           << "<line x1=\"" << f.X(p.x) << "\" y1=\"" << f.Y(p.y) << "\" x2=\"" << f.X(tip.x()) << "\" y2=\""
           << f.Y(tip.y()) << "\"/>\n";
      }
      os << "</g>\n";
    }
  }

  for (const auto& m : scene.markers) {
    if (m.poses.empty()) continue;
    os << "<g stroke=\"" << m.color << "\" fill=\"white\" stroke-width=\"1.5\">\n";
    for (const auto& p : m.poses) {
      os << MarkerShape(m.shape, f.X(p.x), f.Y(p.y), m.size_px);
      if (m.heading_ticks) {
        const Eigen::Vector2d tip = p * Eigen::Vector2d(tick_m, 0.0);
        os << "<line x1=\"" << f.X(p.x) << "\" y1=\"" << f.Y(p.y) << "\" x2=\"" << f.X(tip.x()) << "\" y2=\""
           << f.Y(tip.y()) << "\"/>";
      }
      os << "\n";
    }
    os << "</g>\n";
    if (!m.texts.empty()) {
      os << "<g font-size=\"11\" fill=\"" << m.color << "\">\n";
      for (size_t i = 0; i < m.texts.size() && i < m.poses.size(); ++i)
        os << "<text x=\"" << f.X(m.poses[i].x) + m.size_px + 2.0 << "\" y=\"" << f.Y(m.poses[i].y) - m.size_px - 1.0
           << "\">" << Escape(m.texts[i]) << "</text>\n";
      os << "</g>\n";
    }
  }

  os << "</g>\n";
  // Scale bar under the drawing, at the left.
  const double bar_y = f.Y(b.min_y) + 25.0, bar_x = f.X(b.min_x);
  os << "<g stroke=\"black\" stroke-width=\"2\"><line x1=\"" << bar_x << "\" y1=\"" << bar_y << "\" x2=\""
     << bar_x + bar_m * f.scale << "\" y2=\"" << bar_y << "\"/><line x1=\"" << bar_x << "\" y1=\"" << bar_y - 5
     << "\" x2=\"" << bar_x << "\" y2=\"" << bar_y + 5 << "\"/><line x1=\"" << bar_x + bar_m * f.scale << "\" y1=\""
     << bar_y - 5 << "\" x2=\"" << bar_x + bar_m * f.scale << "\" y2=\"" << bar_y + 5 << "\"/></g>\n";
  std::ostringstream bar_label;
  bar_label << bar_m << " m" << (options.grid ? " (grid spacing)" : "");
  os << "<text x=\"" << bar_x + bar_m * f.scale + 10.0 << "\" y=\"" << bar_y + 5.0 << "\" font-size=\"14\">"
     << Escape(bar_label.str()) << "</text>\n";

  // Legend at the right of the drawing.
  double ly = f.top + 10.0;
  const double lx = f.X(b.max_x) + 25.0;
  os << "<g font-size=\"14\">\n<text x=\"" << lx << "\" y=\"" << ly << "\" font-weight=\"bold\">Legend</text>\n";
  ly += 24.0;
  auto entry_line = [&](const std::string& label, const std::string& color, bool dashed, double width) {
    os << "<line x1=\"" << lx << "\" y1=\"" << ly - 5 << "\" x2=\"" << lx + 30 << "\" y2=\"" << ly - 5
       << "\" stroke=\"" << color << "\" stroke-width=\"" << width << "\""
       << (dashed ? " stroke-dasharray=\"6 4\"" : "") << "/><text x=\"" << lx + 40 << "\" y=\"" << ly << "\">"
       << Escape(label) << "</text>\n";
    ly += 22.0;
  };
  for (const auto& a : scene.areas) {
    if (a.label.empty()) continue;
    os << "<rect x=\"" << lx << "\" y=\"" << ly - 12 << "\" width=\"30\" height=\"12\" fill=\"" << a.color
       << "\" fill-opacity=\"" << a.opacity << "\"/><text x=\"" << lx + 40 << "\" y=\"" << ly << "\">"
       << Escape(a.label) << "</text>\n";
    ly += 22.0;
  }
  for (const auto& l : scene.lines)
    if (!l.label.empty()) entry_line(l.label, l.color, false, std::max(l.width_px, 2.0));
  for (const auto& l : scene.points) {
    if (l.label.empty()) continue;
    os << "<circle cx=\"" << lx + 15 << "\" cy=\"" << ly - 5 << "\" r=\"3\" fill=\"" << l.color
       << "\"/><text x=\"" << lx + 40 << "\" y=\"" << ly << "\">" << Escape(l.label) << "</text>\n";
    ly += 22.0;
  }
  for (const auto& l : scene.links)
    if (!l.label.empty()) entry_line(l.label, l.color, false, 1.0);
  for (const auto& t : scene.trajectories) {
    if (t.label.empty()) continue;
    entry_line(t.label, t.color, t.dashed, t.width_px);
  }
  for (const auto& m : scene.markers) {
    if (m.label.empty()) continue;
    os << "<g stroke=\"" << m.color << "\" fill=\"white\" stroke-width=\"1.5\">"
       << MarkerShape(m.shape, lx + 15.0, ly - 5.0, std::min(m.size_px, 6.0)) << "</g><text x=\"" << lx + 40
       << "\" y=\"" << ly << "\">" << Escape(m.label) << "</text>\n";
    ly += 22.0;
  }
  os << "</g>\n</svg>\n";
  return w.str();
}

}  // namespace minenav
