// SPDX-License-Identifier: MIT
// The corrected ISYBAU copy (isybau_correction.h): edits at byte offsets of the source's UTF-8
// text, found with pugixml (offset_debug: where an element's name begins), applied from the back,
// and the text encoded again as it was read.
#include "sewerplan/core/isybau_correction.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <unordered_set>
#include <vector>

#include <pugixml.hpp>

#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/text_file.h"

#include "isybau_objects.h"
#include "xml_support.h"

namespace sewerplan {
namespace {

using XmlNode = pugi::xml_node;

// Below half a millimetre a value is unchanged: the map's own numbers, read back.
constexpr double kUnchangedM = 5e-4;
constexpr double kMillimetresPerMetre = 1000;

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

// The decimals to write a value with: as many as the file's own value has, 2 to 3 (centimetres
// to millimetres: what a robot's odometry can tell).
int decimals_of(std::string_view original) {
  const std::size_t dot = original.find('.');
  if (dot == std::string_view::npos) return 2;
  return std::clamp(static_cast<int>(original.size() - dot - 1), 2, 3);
}

std::optional<double> number_in(XmlNode element) {
  const std::string text(xml::text(element));
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// An XML comment: "--" may not appear inside, nor may it end with '-'.
std::string comment(std::string_view note) {
  std::string out;
  for (char c : note) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return "<!-- " + out + " -->";
}

// Edits of one text at byte offsets of the elements pugixml found in it.
class Splicer {
 public:
  explicit Splicer(const std::string& text)
      : text_(text), newline_(text.find("\r\n") != std::string::npos ? "\r\n" : "\n") {}

  // A comment before `element`, on a line of its own at the element's indentation.
  bool comment_before(XmlNode element, std::string_view note) {
    return insert_before(element, comment(note));
  }

  // `xml` before `element`, on a line of its own at the element's indentation.
  bool insert_before(XmlNode element, const std::string& xml) {
    const std::optional<std::size_t> lt = open_of(element);
    if (!lt) return false;
    edits_.push_back({*lt, 0, xml + newline_ + indent_before(*lt)});
    return true;
  }

  // Whether set_text can change `element`: an element holding only text, or nothing (one
  // with comments or children inside is not touched).
  bool plain(XmlNode element) const {
    for (XmlNode c = element.first_child(); c; c = c.next_sibling()) {
      if (c.type() != pugi::node_pcdata) return false;
    }
    const std::optional<std::size_t> lt = open_of(element);
    return lt && start_tag_end(*lt);
  }

  // The text of a plain() element replaced by `value`; false (nothing changed) if not plain.
  bool set_text(XmlNode element, const std::string& value) {
    if (!plain(element)) return false;
    const std::size_t lt = *open_of(element);
    const std::optional<std::size_t> gt = start_tag_end(lt);
    if (text_[*gt - 1] == '/') {  // <Laenge/>
      edits_.push_back({*gt - 1, 2, ">" + value + "</" + element.name() + ">"});
      return true;
    }
    const std::size_t content = *gt + 1;
    const std::size_t end = text_.find('<', content);
    if (end == std::string::npos) return false;
    edits_.push_back({content, end - content, value});
    return true;
  }

  // "isy:" for <isy:Profil>: new elements take their neighbour's prefix.
  static std::string prefix_of(XmlNode element) {
    const std::string_view name = element.name();
    const std::size_t colon = name.find(':');
    return colon == std::string_view::npos ? std::string() : std::string(name.substr(0, colon + 1));
  }

  std::string apply() && {
    std::stable_sort(edits_.begin(), edits_.end(),
                     [](const Edit& a, const Edit& b) { return a.at > b.at; });
    std::string out = text_;
    for (const Edit& e : edits_) out.replace(e.at, e.length, e.text);
    return out;
  }

 private:
  struct Edit {
    std::size_t at;
    std::size_t length;
    std::string text;
  };

  // The '<' of `element`'s start tag.
  std::optional<std::size_t> open_of(XmlNode element) const {
    const std::ptrdiff_t name = element.offset_debug();
    if (name <= 0 || static_cast<std::size_t>(name) > text_.size() ||
        text_[static_cast<std::size_t>(name) - 1] != '<') {
      return std::nullopt;
    }
    return static_cast<std::size_t>(name) - 1;
  }

  // The '>' that ends the start tag at `lt` (attribute values may hold one).
  std::optional<std::size_t> start_tag_end(std::size_t lt) const {
    char quote = 0;
    for (std::size_t i = lt; i < text_.size(); ++i) {
      const char c = text_[i];
      if (quote != 0) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        return i;
      }
    }
    return std::nullopt;
  }

  std::string indent_before(std::size_t lt) const {
    std::size_t begin = lt;
    while (begin > 0 && (text_[begin - 1] == ' ' || text_[begin - 1] == '\t')) --begin;
    return text_.substr(begin, lt - begin);
  }

  const std::string& text_;
  std::string newline_;
  std::vector<Edit> edits_;
};

class CorrectionWriter {
 public:
  CorrectionWriter(const std::string& utf8, const SewerMap& base, const CorrectedMap& corrected,
                   const MapMeasurements& measurements, const std::string& file,
                   Diagnostics& diagnostics)
      : splice_(utf8),
        base_(base),
        fixed_(corrected.map),
        corrected_(corrected),
        measurements_(measurements),
        file_(file),
        d_(diagnostics) {}

  void object(XmlNode object) {
    const std::string name(xml::text(xml::child(object, "Objektbezeichnung")));
    const std::string_view kind = xml::text(xml::child(object, "Objektart"));
    if (kind == "1") {
      const XmlNode kante = xml::child(object, "Kante");
      if (xml::text(xml::child(kante, "KantenTyp")) != "0") return;
      // As the importer: the first Haltung of a name is the pipe (a second is a duplicate).
      if (!pipes_done_.insert(name).second) return;
      if (const std::optional<PipeId> id = base_.find_pipe(name)) pipe(kante, *id);
    } else if (kind == "2") {
      if (!nodes_done_.insert(name).second) return;
      if (const std::optional<ManholeId> id = base_.find_manhole(name)) node(object, *id);
    }
  }

  // The corrections ISYBAU has no element for.
  void directions() {
    for (const auto& [found, applied] : corrected_.applied) {
      if (!applied || found.discrepancy.kind != Discrepancy::Kind::kDirectionOff) continue;
      d_.warning(file_, describe(found.discrepancy, base_) +
                            ": not written to the ISYBAU copy (ISYBAU gives a slot's direction by "
                            "its pipe's line, which no robot measured); in the corrected JSON map "
                            "and the discrepancy report");
    }
  }

  void provenance(XmlNode root) {
    std::string note =
        "sewerplan: a corrected copy of " + std::filesystem::path(file_).filename().string() +
        ": values measured by robots written in place (" + std::to_string(lengths) + " lengths, " +
        std::to_string(positions) + " positions, " + std::to_string(diameters) +
        " diameters; each marked by a comment before it), every other byte as it "
        "was. Measurements of map '" +
        measurements_.map_name + "' (geometry fingerprint " + measurements_.map_fingerprint +
        ") by:";
    for (const MeasurementSource& s : measurements_.sources) {
      note += " robot " + s.robot + ", mission " + s.mission + ", " + s.date + ";";
    }
    splice_.comment_before(root, note);
  }

  std::string text() && { return std::move(splice_).apply(); }

  std::size_t lengths = 0;
  std::size_t positions = 0;
  std::size_t diameters = 0;

 private:
  void not_written(XmlNode at, const std::string& what) {
    d_.warning(file_ + ":" + xml::path(at), what + ": not written to the ISYBAU copy");
  }

  void pipe(XmlNode kante, PipeId id) {
    const Pipe& was = base_.pipe(id);
    const Pipe& now = fixed_.pipe(*fixed_.find_pipe(was.name));
    if (std::abs(now.length_m - was.length_m) > kUnchangedM) length(kante, id, now.length_m);
    if (std::abs(now.diameter_m - was.diameter_m) > kUnchangedM) diameter(kante, was, now);
  }

  // Laenge, else the Rohrlaenge or DMPLaenge the importer falls back on, else a new Laenge.
  void length(XmlNode kante, PipeId id, double length_m) {
    const Pipe& was = base_.pipe(id);
    std::string note = "sewerplan: length measured " + fixed(length_m, 2) + " m";
    for (const PipeMeasurement& m : measurements_.pipes) {
      if (m.pipe != id) continue;
      note += " (sigma " + fixed(std::sqrt(m.length_m.variance), 2) + " m, " +
              std::to_string(m.length_m.count) + " drives)";
    }
    note += "; the map said " + fixed(was.length_m, 2) + " m";
    XmlNode target = xml::child(kante, "Laenge");
    for (std::string_view other : {"Rohrlaenge", "DMPLaenge"}) {
      if (!target) target = detail::find_below(kante, other);
    }
    if (target) {
      if (splice_.set_text(target, fixed(length_m, decimals_of(xml::text(target)))) &&
          splice_.comment_before(target, note)) {
        ++lengths;
        return;
      }
      return not_written(target, "pipe " + was.name + ": " + note);
    }
    const XmlNode profil = xml::child(kante, "Profil");
    const std::string p = Splicer::prefix_of(profil);
    // Two insertions at one place land in the reverse order of their calls: the comment first.
    if (profil &&
        splice_.insert_before(profil,
                              "<" + p + "Laenge>" + fixed(length_m, 2) + "</" + p + "Laenge>") &&
        splice_.insert_before(profil, comment(note))) {
      ++lengths;
      return;
    }
    not_written(kante, "pipe " + was.name + ": " + note);
  }

  // diameter = the smaller of Profilbreite and Profilhoehe (mm): a smaller diameter is the
  // Profilbreite (a circle's Profilhoehe too), the height of another shape stays.
  void diameter(XmlNode kante, const Pipe& was, const Pipe& now) {
    const XmlNode profil = xml::child(kante, "Profil");
    const std::string mm = fixed(now.diameter_m * kMillimetresPerMetre, 0);
    const std::string note = "sewerplan: diameter measured " + fixed(now.diameter_m, 2) +
                             " m; the map said " + fixed(was.diameter_m, 2) + " m";
    std::vector<XmlNode> targets;
    if (const XmlNode breite = xml::child(profil, "Profilbreite")) targets.push_back(breite);
    const XmlNode hoehe = xml::child(profil, "Profilhoehe");
    if (hoehe && was.shape == PipeShape::kCircular) targets.push_back(hoehe);
    const bool writable =
        !targets.empty() &&
        std::all_of(targets.begin(), targets.end(), [&](XmlNode t) { return splice_.plain(t); });
    if (!writable || !splice_.comment_before(profil, note)) {
      return not_written(profil ? profil : kante, "pipe " + was.name + ": " + note);
    }
    for (XmlNode t : targets) (void)splice_.set_text(t, mm);
    ++diameters;
  }

  // Rechtswert and Hochwert of the node's Punkte moved by the measured shift: a zone in front of
  // a UTM Rechtswert (isybau_geometry.h) stays. The pipes' lines are not moved: no robot measured
  // them (a moved node's slot directions follow from them as before).
  void node(XmlNode object, ManholeId id) {
    const Manhole& was = base_.manhole(id);
    const Manhole& now = fixed_.manhole(*fixed_.find_manhole(was.name));
    const double dx = now.position.x_m - was.position.x_m;
    const double dy = now.position.y_m - was.position.y_m;
    if (std::abs(dx) <= kUnchangedM && std::abs(dy) <= kUnchangedM) return;
    const std::string note = "sewerplan: position measured " + fixed(now.position.x_m, 2) + ", " +
                             fixed(now.position.y_m, 2) + "; the map said " +
                             fixed(was.position.x_m, 2) + ", " + fixed(was.position.y_m, 2);
    // Every Punkt of the node (cover, floor) moves with it; the first gives its position.
    const XmlNode point = detail::isybau_position_point(object);
    std::vector<XmlNode> points;
    for (XmlNode p = point; p; p = p.next_sibling()) {
      if (xml::local_name(p) == "Punkt") points.push_back(p);
    }
    const auto movable = [&](XmlNode p) {
      const XmlNode r = xml::child(p, "Rechtswert");
      const XmlNode h = xml::child(p, "Hochwert");
      return number_in(r) && number_in(h) && splice_.plain(r) && splice_.plain(h);
    };
    if (!point || !movable(point) || !splice_.comment_before(point, note)) {
      return not_written(point ? point : object, "node " + was.name + ": " + note);
    }
    for (XmlNode p : points) {
      if (!movable(p)) continue;  // a point without coordinates: nothing to move
      for (const auto& [name, shift] : {std::pair{"Rechtswert", dx}, std::pair{"Hochwert", dy}}) {
        const XmlNode v = xml::child(p, name);
        (void)splice_.set_text(v, fixed(*number_in(v) + shift, decimals_of(xml::text(v))));
      }
    }
    ++positions;
  }

  Splicer splice_;
  const SewerMap& base_;
  const SewerMap& fixed_;
  const CorrectedMap& corrected_;
  const MapMeasurements& measurements_;
  const std::string& file_;
  Diagnostics& d_;
  std::unordered_set<std::string> pipes_done_;
  std::unordered_set<std::string> nodes_done_;
};

// `corrected` has every pipe and manhole of `base`, by name.
Result<void> same_objects(const SewerMap& base, const CorrectedMap& corrected,
                          const std::string& file) {
  const auto missing = [&](const std::string& what) {
    return Error{ErrorCode::kInvalidArgument,
                 file + ": the corrected map '" + corrected.map.name() + "' has no " + what +
                     " of this ISYBAU file: it was not made from this file's map"};
  };
  for (PipeId p : base.pipe_ids()) {
    if (!corrected.map.find_pipe(base.pipe(p).name)) return missing("pipe " + base.pipe(p).name);
  }
  for (ManholeId m : base.manhole_ids()) {
    if (!corrected.map.find_manhole(base.manhole(m).name)) {
      return missing("manhole " + base.manhole(m).name);
    }
  }
  return {};
}

}  // namespace

Result<IsybauCorrection> correct_isybau(std::string_view source, const std::string& file_name,
                                        const CorrectedMap& corrected,
                                        const MapMeasurements& measurements,
                                        Diagnostics& diagnostics,
                                        const IsybauImportOptions& options) {
  Diagnostics reading;  // the file's own warnings were said when it was read as the map
  Result<SewerMap> base = read_map_isybau(source, file_name, reading, options);
  if (!base.has_value()) return base.error();
  const std::string fingerprint = map_geometry_fingerprint(*base);
  if (fingerprint != measurements.map_fingerprint) {
    return Error{ErrorCode::kInvalidArgument,
                 file_name + ": the measurements are of map '" + measurements.map_name +
                     "' (geometry fingerprint " + measurements.map_fingerprint +
                     "), not of the map this ISYBAU file gives, '" + base->name() +
                     "' (fingerprint " + fingerprint + ")"};
  }
  if (Result<void> same = same_objects(*base, corrected, file_name); !same.has_value()) {
    return same.error();
  }
  TextDecoding how;
  Result<std::string> utf8 = text_to_utf8(source, xml::declared_encoding(source), file_name, how);
  if (!utf8.has_value()) return utf8.error();
  if (how.replaced > 0) {
    return Error{ErrorCode::kUnsupportedFormat,
                 file_name + ": " + std::to_string(how.replaced) + " bytes are no character in " +
                     how.encoding + ": a corrected copy could not keep them as they are"};
  }
  pugi::xml_document doc;
  if (!doc.load_buffer(utf8->data(), utf8->size(), pugi::parse_default, pugi::encoding_utf8)) {
    return Error{ErrorCode::kParse, file_name + ": XML is not well-formed"};  // read above
  }
  CorrectionWriter writer(*utf8, *base, corrected, measurements, file_name, diagnostics);
  for (XmlNode object : detail::isybau_objects(doc.document_element())) writer.object(object);
  writer.directions();
  writer.provenance(doc.document_element());
  IsybauCorrection out{
      .lengths = writer.lengths, .positions = writer.positions, .diameters = writer.diameters};
  Result<std::string> encoded = utf8_to_text(std::move(writer).text(), how.encoding, file_name);
  if (!encoded.has_value()) return encoded.error();
  out.text = std::string(source.substr(0, byte_order_mark(source).size)) + *encoded;
  return out;
}

}  // namespace sewerplan
