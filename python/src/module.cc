// SPDX-License-Identifier: MIT
// The sewerplan Python module: errors, maps, robot profiles and missions (bindings.h says why the
// module is split into three files).
#include <array>
#include <cctype>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/server/documents.h"
#include "sewerplan/version.h"
#ifdef SEWERPLAN_WITH_GIS
#include "sewerplan/gis/map_source.h"
#endif

#include "bindings.h"
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

namespace sewerplan::python {
namespace {

#ifdef SEWERPLAN_WITH_GIS
constexpr bool kHasGis = true;
#else
constexpr bool kHasGis = false;
#endif

// The reader the sewerplan command uses for `path` (gis/map_source.h); without GIS, the same
// fallback as the command's (core/map_io.h: read_map_without_gis).
Result<SewerMap> read_any_map(const std::filesystem::path& path,
                              const std::optional<std::filesystem::path>& gis_fields,
                              Diagnostics& diagnostics) {
#ifdef SEWERPLAN_WITH_GIS
  return gis::read_map_source(path, diagnostics, gis_fields);
#else
  return read_map_without_gis(path, diagnostics, gis_fields);
#endif
}

constexpr std::size_t kErrorCodeCount = static_cast<std::size_t>(ErrorCode::kBusError) + 1;

// Set once at import: sewerplan.Error, and the subclass each error code raises.
PyObject* error_type = nullptr;
std::array<PyObject*, kErrorCodeCount> error_types{};

// The exception class of each library error code, grouped as the CLI's exit codes group them
// (server::exit_code_for, docs/cli.md): `except sewerplan.Error` catches them all,
// `except sewerplan.InvalidInputError` every bad file (exit 1), and so on.
struct ErrorClass {
  const char* name;
  const char* group;  // the exit code's class, or nullptr: a direct subclass of Error
  const char* doc;
};

ErrorClass error_class(ErrorCode code) {
  switch (code) {
    case ErrorCode::kIo:
      return {"IoError", nullptr, "A file could not be read or written (code 'io', exit code 3)."};
    case ErrorCode::kParse:
      return {"ParseError", "InvalidInputError",
              "A file is not well-formed in its format (code 'parse', exit code 1)."};
    case ErrorCode::kInvalidMap:
      return {"InvalidMapError", "InvalidInputError",
              "A map is well-formed but inconsistent (code 'invalid-map', exit code 1)."};
    case ErrorCode::kInvalidMission:
      return {"InvalidMissionError", "InvalidInputError",
              "A mission names unknown objects or is inconsistent (code 'invalid-mission', exit "
              "code 1)."};
    case ErrorCode::kInvalidProfile:
      return {"InvalidProfileError", "InvalidInputError",
              "A robot profile is missing or has impossible values (code 'invalid-profile', exit "
              "code 1)."};
    case ErrorCode::kUnsupportedFormat:
      return {"UnsupportedFormatError", "InvalidInputError",
              "A file format sewerplan does not read or write (code 'unsupported-format', exit "
              "code 1)."};
    case ErrorCode::kInvalidArgument:
      return {"InvalidArgumentError", nullptr,
              "An argument outside its documented range, or a name the map lacks (code "
              "'invalid-argument', the CLI's usage error, exit code 2); also a ValueError."};
    case ErrorCode::kNoPlan:
      return {"NoPlanError", nullptr,
              "No plan exists: a task, every exit or the battery is out of reach (code 'no-plan', "
              "exit code 4)."};
    case ErrorCode::kSearchLimit:
      return {"SearchLimitError", "SearchStoppedError",
              "The search stopped at its time or expansion limit without a plan (code "
              "'search-limit', exit code 5)."};
    case ErrorCode::kCancelled:
      return {"CancelledError", "SearchStoppedError",
              "The search was cancelled (CancelToken) without a plan (code 'cancelled', exit "
              "code 5)."};
    case ErrorCode::kCanTimeout:
      return {"CanTimeoutError", "IoError",
              "A CAN peer did not answer within its deadline (code 'can-timeout', exit code 3)."};
    case ErrorCode::kBusError:
      return {"BusError", "IoError",
              "A CAN bus or adapter failed (code 'bus-error', exit code 3)."};
  }
  return {"Error", nullptr, ""};
}

// A diagnostic's place, split: "map.json:$.pipes[3]" -> file, path; "a.sewer:12" or
// "m.json:3:7" -> file, line (and column); anything else: file only.
struct Where {
  std::string file;
  std::optional<int> line;
  std::optional<std::string> path;
};

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  return true;
}

Where split_where(const std::string& where) {
  if (const auto dollar = where.find(":$"); dollar != std::string::npos) {
    return {where.substr(0, dollar), std::nullopt, where.substr(dollar + 1)};
  }
  std::string rest = where;
  std::vector<std::string> numbers;
  while (numbers.size() < 2) {
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos || !all_digits(rest.substr(colon + 1))) break;
    numbers.push_back(rest.substr(colon + 1));
    rest = rest.substr(0, colon);
  }
  if (numbers.empty()) return {where, std::nullopt, std::nullopt};
  return {rest, std::stoi(numbers.back()), std::nullopt};
}

py::dict profile_dict(const RobotProfile& p) {
  py::dict d;
  d["name"] = p.name;
  d["length_m"] = p.length_m;
  d["segment_count"] = p.segment_count;
  d["body_width_m"] = p.body_width_m;
  d["symmetric"] = p.symmetric;
  d["min_pipe_diameter_m"] = p.min_pipe_diameter_m;
  d["max_pipe_diameter_m"] = p.max_pipe_diameter_m;
  d["max_step_m"] = p.max_step_m;
  d["max_turn_deg"] = p.max_turn_deg;
  d["joint_yaw_max_deg"] = p.joint_yaw_max_deg;
  d["joint_pitch_max_deg"] = p.joint_pitch_max_deg;
  d["speed_mps"] = p.speed_mps;
  d["inspection_speed_mps"] = p.inspection_speed_mps;
  d["manhole_pass_s"] = p.manhole_pass_s;
  d["manoeuvre_speed_mps"] = p.manoeuvre_speed_mps;
  d["turn_s_per_deg"] = p.turn_s_per_deg;
  d["step_s_per_m"] = p.step_s_per_m;
  d["sample_s"] = p.sample_s;
  d["battery_wh"] = p.battery_wh;
  d["power_w"] = p.power_w;
  return d;
}

std::string task_place(const Task& task, const SewerMap& map) { return describe(task.place, map); }

std::shared_ptr<MissionHandle> mission_from_json(std::shared_ptr<const SewerMap> map,
                                                 const std::string& text,
                                                 const std::string& file_name) {
  Diagnostics diagnostics;
  Mission mission =
      value_or_raise(read_mission_json(text, file_name, *map, diagnostics), &diagnostics);
  return std::make_shared<MissionHandle>(MissionHandle{std::move(map), std::move(mission)});
}

std::string mission_json(const MissionHandle& h) {
  std::ostringstream out;
  write_mission_json(h.mission, *h.map, out);
  return out.str();
}

void bind_errors(py::module_& m) {
  // Never destroyed: the types live as long as the interpreter, which may end after this
  // library's static destructors.
  auto* base = new py::exception<Error>(m, "Error", PyExc_RuntimeError);
  error_type = base->ptr();
  py::setattr(*base, "__doc__",
              py::str("Every failure of the library: .code (the error's name, as the CLI's --json "
                      "names it), .exit_code (the CLI's exit code for it), .message and "
                      ".diagnostics (each Diagnostic naming its file and line or JSON path). A "
                      "subclass per code (ParseError, NoPlanError, ...), grouped as the exit codes "
                      "are (InvalidInputError: 1, IoError: 3, SearchStoppedError: 5)."));
  py::setattr(*base, "code", py::none());
  py::setattr(*base, "exit_code", py::none());
  const auto new_type = [&m](const char* name, const char* doc, py::tuple bases) {
    const std::string qualified = std::string("sewerplan.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
    if (type == nullptr) throw py::error_already_set();
    m.add_object(name, py::handle(type));  // the module holds the reference
    return type;
  };
  const py::handle base_type(error_type);
  new_type("InvalidInputError",
           "An input that does not parse or validate (exit code 1): ParseError, InvalidMapError, "
           "InvalidMissionError, InvalidProfileError, UnsupportedFormatError.",
           py::make_tuple(base_type));
  py::setattr(m.attr("InvalidInputError"), "exit_code", py::int_(int{server::kExitInvalidInput}));
  new_type("SearchStoppedError",
           "The search stopped without a plan (exit code 5): SearchLimitError, CancelledError.",
           py::make_tuple(base_type));
  py::setattr(m.attr("SearchStoppedError"), "exit_code", py::int_(int{server::kExitSearchLimit}));
  for (std::size_t i = 0; i < kErrorCodeCount; ++i) {
    const auto code = static_cast<ErrorCode>(i);
    const ErrorClass c = error_class(code);
    py::tuple bases = c.group != nullptr ? py::make_tuple(m.attr(c.group))
                      : code == ErrorCode::kInvalidArgument
                          ? py::make_tuple(base_type, py::handle(PyExc_ValueError))
                          : py::make_tuple(base_type);
    PyObject* type = new_type(c.name, c.doc, bases);
    py::handle handle(type);
    py::setattr(handle, "code", py::str(std::string(to_string(code))));
    py::setattr(handle, "exit_code", py::int_(server::exit_code_for(Error{code, {}})));
    error_types[i] = type;
  }
  py::class_<Diagnostic>(m, "Diagnostic", "A problem found in an input file, naming where.")
      .def_property_readonly(
          "severity",
          [](const Diagnostic& d) { return d.severity == Severity::kError ? "error" : "warning"; },
          "'error' or 'warning'.")
      .def_readonly("where", &Diagnostic::where, "Where: 'map.json:$.pipes[1]', 'a.sewer:12'.")
      .def_readonly("message", &Diagnostic::message, "What is wrong, naming the object.")
      .def_property_readonly(
          "file", [](const Diagnostic& d) { return split_where(d.where).file; },
          "The file of `where`.")
      .def_property_readonly(
          "line", [](const Diagnostic& d) { return split_where(d.where).line; },
          "The line (from 1) in a text format or a JSON syntax error, else None.")
      .def_property_readonly(
          "path", [](const Diagnostic& d) { return split_where(d.where).path; },
          "The JSON path of the field ('$.pipes[1].length_m'), else None.")
      .def("__str__",
           [](const Diagnostic& d) {
             std::ostringstream out;
             out << d;
             return out.str();
           })
      .def("__repr__", [](const Diagnostic& d) {
        std::ostringstream out;
        out << "<Diagnostic " << d << '>';
        return out.str();
      });
  py::class_<CancelToken>(m, "CancelToken", "A cancel flag for plan(), settable from any thread.")
      .def(py::init<>(), "A token not cancelled.")
      .def("cancel", &CancelToken::cancel,
           "Stops the plan() (or Replanner call) given this token: it raises CancelledError.")
      .def_property_readonly("cancelled", &CancelToken::cancelled, "Whether cancel() was called.")
      .def("__repr__",
           [](const CancelToken& t) {
             return Repr("CancelToken").field("cancelled", t.cancelled()).str();
           })
      .def("wait_entered", &CancelToken::wait_entered, py::call_guard<py::gil_scoped_release>(),
           "Blocks until a call given this token runs without the GIL.");
}

void bind_map_types(py::module_& m) {
  py::class_<Position>(m, "Position", "A point in the map's coordinates, in metres.")
      .def_readonly("x_m", &Position::x_m, "Easting (m).")
      .def_readonly("y_m", &Position::y_m, "Northing (m).")
      .def_readonly("z_m", &Position::z_m, "Height (m).")
      .def("__repr__", [](const Position& p) {
        return Repr("Position").field("x_m", p.x_m).field("y_m", p.y_m).field("z_m", p.z_m).str();
      });
  py::class_<Manhole>(m, "Manhole", "A manhole: where pipes meet and the robot turns or exits.")
      .def_readonly("name", &Manhole::name, "The manhole's name.")
      .def_readonly("position", &Manhole::position, "Its Position.")
      .def_readonly("diameter_m", &Manhole::diameter_m, "Inner diameter (m).")
      .def_readonly("exit", &Manhole::exit, "Whether the robot may leave the sewer here.")
      .def_property_readonly(
          "slot_count", [](const Manhole& mh) { return int{mh.slot_count}; },
          "How many pipe mouths (slots, numbered from 0) it has.")
      .def("__repr__", [](const Manhole& mh) {
        return Repr("Manhole")
            .word(mh.name)
            .field("slots", int{mh.slot_count})
            .field("exit", mh.exit)
            .str();
      });
  py::class_<InspectionPoint>(m, "InspectionPoint", "A named point in a pipe (a task's place).")
      .def_readonly("name", &InspectionPoint::name, "The point's name.")
      .def_readonly("offset_m", &InspectionPoint::offset_m,
                    "Distance from the pipe's first end (m).")
      .def("__repr__", [](const InspectionPoint& p) {
        return Repr("InspectionPoint").word(p.name).field("offset_m", p.offset_m).str();
      });
}

void bind_map(py::module_& m) {
  py::class_<SewerMap, std::shared_ptr<SewerMap>>(
      m, "SewerMap", "A sewer network: manholes, pipes, inspection points (immutable).")
      .def_property_readonly("name", &SewerMap::name, "The network's name.")
      .def_property_readonly(
          "crs",
          [](const SewerMap& map) -> std::optional<std::string> {
            if (!map.crs()) return std::nullopt;
            return map.crs()->to_string();
          },
          "The coordinate reference system ('EPSG:25832'), or None.")
      .def_property_readonly("manhole_count", &SewerMap::manhole_count, "How many manholes.")
      .def_property_readonly("pipe_count", &SewerMap::pipe_count, "How many pipes.")
      .def_property_readonly("point_count", &SewerMap::point_count, "Inspection points.")
      .def_property_readonly("finding_count", &SewerMap::finding_count,
                             "Inspection findings (read_condition).")
      .def_property_readonly(
          "manholes",
          [](const SewerMap& map) {
            return std::vector<Manhole>(map.manholes().begin(), map.manholes().end());
          },
          "Every Manhole, in the map's order.")
      .def_property_readonly(
          "points",
          [](const SewerMap& map) {
            return std::vector<InspectionPoint>(map.points().begin(), map.points().end());
          },
          "Every InspectionPoint.")
      .def_property_readonly(
          "pipes",
          [](const SewerMap& map) {
            py::list pipes;
            for (const Pipe& pipe : map.pipes()) {
              py::dict d;
              d["name"] = pipe.name;
              d["length_m"] = pipe.length_m;
              d["diameter_m"] = pipe.diameter_m;
              d["shape"] = std::string(to_string(pipe.shape));
              for (std::size_t end = 0; end < 2; ++end) {
                const auto& manhole = pipe.ends[end].manhole;
                d[end == 0 ? "from" : "to"] =
                    manhole ? py::object(py::str(map.manhole(*manhole).name)) : py::none();
              }
              pipes.append(d);
            }
            return pipes;
          },
          "Each pipe as a dict: name, from, to (manhole names or None), length_m, diameter_m, "
          "shape.")
      .def_property_readonly(
          "exits",
          [](const SewerMap& map) {
            std::vector<std::string> names;
            for (const Manhole& mh : map.manholes()) {
              if (mh.exit) names.push_back(mh.name);
            }
            return names;
          },
          "The names of the exit manholes.")
      .def(
          "kind_of",
          [](const SewerMap& map, const std::string& name) -> std::optional<std::string> {
            if (map.find_manhole(name)) return "manhole";
            if (map.find_pipe(name)) return "pipe";
            if (map.find_point(name)) return "point";
            return std::nullopt;
          },
          "'manhole', 'pipe', 'point', or None for a name the map does not have.")
      .def(
          "to_json",
          [](const SewerMap& map) {
            std::ostringstream out;
            write_map_json(map, out);
            return out.str();
          },
          "The map in its JSON format (docs/formats/map-json.md).")
      .def(
          "__eq__",
          [](const SewerMap& a, const py::object& other) {
            return py::isinstance<SewerMap>(other) && a == other.cast<const SewerMap&>();
          },
          py::arg("other"), "Whether two maps hold the same network (False for a non-map).")
      .def("__repr__", [](const SewerMap& map) {
        Repr repr("SewerMap");
        repr.word(map.name())
            .field("manholes", map.manhole_count())
            .field("pipes", map.pipe_count())
            .field("points", map.point_count());
        if (map.finding_count() > 0) repr.field("findings", map.finding_count());
        return repr.str();
      });

  m.def(
      "read_map",
      [](const std::filesystem::path& path,
         const std::optional<std::filesystem::path>& gis_fields) {
        Diagnostics diagnostics;
        return std::make_shared<SewerMap>(
            value_or_raise(read_any_map(path, gis_fields, diagnostics), &diagnostics));
      },
      py::arg("path"), py::arg("gis_fields") = py::none(),
      "Reads a map in any format sewerplan knows (JSON, .sewer, SWMM .inp, ISYBAU .xml) or, "
      "when built with GIS (has_gis), a GeoPackage, a Shapefile or a directory of them through "
      "GDAL, as the sewerplan command does; gis_fields: their field mapping file instead of the "
      "one beside the source (docs/formats/gis-layers.md).");
  m.attr("has_gis") = kHasGis;
  m.def(
      "read_condition",
      [](const SewerMap& map, const std::filesystem::path& path) {
        Diagnostics diagnostics;
        return std::make_shared<SewerMap>(
            value_or_raise(read_condition(map, path, diagnostics), &diagnostics));
      },
      py::arg("map"), py::arg("path"),
      "A copy of `map` with the inspection findings of an ISYBAU Zustandsdaten file joined to "
      "its pipes by name (sewerplan --condition).");
  m.def(
      "parse_map",
      [](const std::string& text, const std::string& file_name, const std::string& format) {
        const std::optional<MapFormat> f = map_format_from_name(format);
        if (!f) raise_error({ErrorCode::kUnsupportedFormat, "unknown map format '" + format + "'"});
        Diagnostics diagnostics;
        return std::make_shared<SewerMap>(
            value_or_raise(parse_map(text, file_name, *f, diagnostics), &diagnostics));
      },
      py::arg("text"), py::arg("file_name") = "<string>", py::arg("format") = "json",
      "Reads a map from text; format: 'json', 'ascii', 'swmm' or 'isybau'.");
  m.def(
      "write_map",
      [](const SewerMap& map, const std::filesystem::path& path,
         const std::optional<std::string>& format) {
        std::optional<MapFormat> f;
        if (format) {
          f = map_format_from_name(*format);
          if (!f) {
            raise_error({ErrorCode::kUnsupportedFormat, "unknown map format '" + *format + "'"});
          }
        }
        const Result<void> written = write_map(map, path, f);
        if (!written.has_value()) raise_error(written.error());
      },
      py::arg("map"), py::arg("path"), py::arg("format") = py::none(),
      "Writes a map as JSON or the ASCII database (the extension decides without format).");
  m.def(
      "write_text_file",
      [](const std::filesystem::path& path, const std::string& text) {
        const Result<void> written = write_text_file(path, text);
        if (!written.has_value()) raise_error(written.error());
      },
      py::arg("path"), py::arg("text"),
      "Writes text as a whole file, atomically (core/output_file.h): a failure raises IoError "
      "(code 'io') naming the file and the reason.");
  m.def(
      "generate_network",
      [](std::size_t manholes, std::uint64_t seed, const std::string& topology) {
        GeneratorOptions options;
        options.manholes = manholes;
        options.seed = seed;
        const std::optional<Topology> t = topology_from_string(topology);
        if (!t) raise_error({ErrorCode::kInvalidArgument, "unknown topology '" + topology + "'"});
        options.topology = *t;
        return std::make_shared<SewerMap>(value_or_raise(generate_network(options)));
      },
      py::arg("manholes"), py::arg("seed") = 1, py::arg("topology") = "meshed",
      "A seeded synthetic network of about `manholes` manholes (sewerplan generate); topology: "
      "'meshed' or 'tree'.");
}

void bind_profile(py::module_& m) {
  py::class_<RobotProfile>(m, "RobotProfile", "What a robot can do and what its actions cost.")
      .def(py::init([](const std::string& name) {
             std::optional<RobotProfile> p = builtin_profile(name);
             if (!p)
               raise_error({ErrorCode::kInvalidProfile, "no built-in profile '" + name + "'"});
             return *p;
           }),
           py::arg("name") = "makro-1.1", "A built-in profile: 'makro-1.1' or 'makro-plus'.")
      .def_readwrite("name", &RobotProfile::name, "The profile's name.")
      .def_readwrite("speed_mps", &RobotProfile::speed_mps, "Driving speed in pipes (m/s).")
      .def_readwrite("inspection_speed_mps", &RobotProfile::inspection_speed_mps,
                     "Speed while inspecting a pipe (m/s).")
      .def_readwrite("battery_wh", &RobotProfile::battery_wh, "Battery capacity (Wh).")
      .def_readwrite("power_w", &RobotProfile::power_w, "Power drawn while working (W).")
      .def_readwrite("min_pipe_diameter_m", &RobotProfile::min_pipe_diameter_m,
                     "The narrowest pipe it drives (m).")
      .def_readwrite("max_pipe_diameter_m", &RobotProfile::max_pipe_diameter_m,
                     "The widest pipe it drives (m).")
      .def_readwrite("max_step_m", &RobotProfile::max_step_m,
                     "The highest step between a pipe and a manhole it climbs (m).")
      .def_readwrite("max_turn_deg", &RobotProfile::max_turn_deg,
                     "The sharpest turn in a manhole it makes (degrees).")
      .def_readwrite("sample_s", &RobotProfile::sample_s, "Time to take a water sample (s).")
      .def("to_dict", &profile_dict,
           "Every field, as the mission format's profile object takes them.")
      .def("__repr__", [](const RobotProfile& p) {
        return Repr("RobotProfile")
            .word(p.name)
            .field("speed_mps", p.speed_mps)
            .field("battery_wh", p.battery_wh)
            .field("power_w", p.power_w)
            .str();
      });
  m.def("builtin_profile_names", &builtin_profile_names,
        "The names RobotProfile() and a mission's profile take: 'makro-1.1', 'makro-plus'.");
}

void bind_mission(py::module_& m) {
  py::class_<Task>(m, "Task", "One task of a mission.")
      .def_readonly("name", &Task::name, "The task's name.")
      .def_property_readonly(
          "kind", [](const Task& t) { return std::string(to_string(t.kind)); },
          "'go_to', 'inspect_pipe' or 'take_water_sample'.")
      .def_readonly("final", &Task::final, "Done last: the mission ends there.")
      .def("__repr__", [](const Task& t) {
        Repr repr("Task");
        repr.word(t.name).field("kind", std::string(to_string(t.kind)));
        if (t.final) repr.field("final", true);
        return repr.str();
      });
  py::class_<MissionHandle, std::shared_ptr<MissionHandle>>(
      m, "Mission", "What an operator asks of the robot on one map (it keeps its map).")
      .def_static("from_json", &mission_from_json, py::arg("map"), py::arg("text"),
                  py::arg("file_name") = "<string>",
                  "Reads a mission in the JSON format (docs/formats/mission-json.md).")
      .def_property_readonly(
          "map", [](const MissionHandle& h) { return h.map; }, "The SewerMap it is on.")
      .def_property_readonly(
          "name", [](const MissionHandle& h) { return h.mission.name; }, "The mission's name.")
      .def_property_readonly(
          "profile", [](const MissionHandle& h) { return h.mission.profile; },
          "The RobotProfile (a copy).")
      .def_property_readonly(
          "tasks", [](const MissionHandle& h) { return h.mission.tasks; }, "Every Task, in order.")
      .def(
          "task_place",
          [](const MissionHandle& h, const std::string& name) {
            for (const Task& t : h.mission.tasks) {
              if (t.name == name) return task_place(t, *h.map);
            }
            raise_error({ErrorCode::kInvalidArgument, "no task '" + name + "'"});
          },
          py::arg("task"), "Where a task is done, as people read it: 'pipe P4'.")
      .def_property_readonly(
          "start", [](const MissionHandle& h) { return describe(h.mission.start, *h.map); },
          "Where the robot starts, as people read it: 'pipe P12'.")
      .def_property_readonly(
          "exits",
          [](const MissionHandle& h) {
            std::vector<std::string> names;
            for (ManholeId id : h.mission.exits) names.push_back(h.map->manhole(id).name);
            return names;
          },
          "The names of the manholes the robot may leave by.")
      .def_property_readonly(
          "battery_reserve",
          [](const MissionHandle& h) { return h.mission.battery_reserve_fraction; },
          "The fraction of the battery kept for the way out (0 to 1).")
      .def("to_json", &mission_json, "The mission in its JSON format.")
      .def("__repr__", [](const MissionHandle& h) {
        return Repr("Mission")
            .word(h.mission.name)
            .field("map", h.map->name())
            .field("start", describe(h.mission.start, *h.map))
            .field("tasks", h.mission.tasks.size())
            .field("profile", h.mission.profile.name)
            .str();
      });
  m.def(
      "read_mission",
      [](std::shared_ptr<const SewerMap> map, const std::filesystem::path& path) {
        Diagnostics diagnostics;
        Mission mission = value_or_raise(read_mission(path, *map, diagnostics), &diagnostics);
        return std::make_shared<MissionHandle>(MissionHandle{std::move(map), std::move(mission)});
      },
      py::arg("map"), py::arg("path"), "Reads a mission file against its map.");
  m.def(
      "generate_mission",
      [](std::shared_ptr<const SewerMap> map, std::size_t tasks, std::uint64_t seed,
         const std::string& profile) {
        domain::MissionOptions options;
        options.tasks = tasks;
        options.seed = seed;
        options.profile = profile;
        Mission mission = value_or_raise(domain::generate_mission(*map, options));
        return std::make_shared<MissionHandle>(MissionHandle{std::move(map), std::move(mission)});
      },
      py::arg("map"), py::arg("tasks") = 5, py::arg("seed") = 1, py::arg("profile") = "makro-plus",
      "A seeded mission on a map (sewerplan generate --mission-tasks).");
}

}  // namespace

void CancelToken::mark_entered() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    entered_ = true;
  }
  entered_cv_.notify_all();
}

void CancelToken::wait_entered() {
  std::unique_lock<std::mutex> lock(mutex_);
  entered_cv_.wait(lock, [this] { return entered_; });
}

void raise_error(const Error& error, const Diagnostics* diagnostics) {
  std::string message = error.message;
  if (message.empty() && diagnostics != nullptr) message = diagnostics->error_summary();
  const auto index = static_cast<std::size_t>(error.code);
  PyObject* const class_of_code = index < kErrorCodeCount ? error_types[index] : error_type;
  py::object type = py::reinterpret_borrow<py::object>(class_of_code);
  py::object exception = type(message);
  exception.attr("code") = std::string(to_string(error.code));
  exception.attr("exit_code") = server::exit_code_for(error);
  exception.attr("message") = message;
  exception.attr("diagnostics") =
      diagnostics != nullptr ? diagnostics->all() : std::vector<Diagnostic>{};
  PyErr_SetObject(class_of_code, exception.ptr());
  throw py::error_already_set();
}

ManholeId manhole_named(const SewerMap& map, const std::string& name) {
  const std::optional<ManholeId> id = map.find_manhole(name);
  if (!id) raise_error({ErrorCode::kInvalidArgument, "no manhole '" + name + "' in the map"});
  return *id;
}

PipeId pipe_named(const SewerMap& map, const std::string& name) {
  const std::optional<PipeId> id = map.find_pipe(name);
  if (!id) raise_error({ErrorCode::kInvalidArgument, "no pipe '" + name + "' in the map"});
  return *id;
}

void bind_maps(py::module_& m) {
  bind_errors(m);
  bind_map_types(m);
  bind_map(m);
  bind_profile(m);
  bind_mission(m);
}

}  // namespace sewerplan::python

PYBIND11_MODULE(_sewerplan, m) {
  m.doc() = "sewerplan: planning and replanning for autonomous sewer-inspection robots";
  m.attr("__version__") = std::string(sewerplan::kVersion);
  // Classes and functions say they are sewerplan's (help(), reprs, signatures, the stubs), the
  // package users import, not its extension's: pybind11 takes their __module__ from the scope's
  // __name__ while they are bound.
  const pybind11::object extension_name = m.attr("__name__");
  m.attr("__name__") = "sewerplan";
  sewerplan::python::bind_maps(m);
  sewerplan::python::bind_planning(m);
  sewerplan::python::bind_simulation(m);
  m.attr("__name__") = extension_name;
}
