// The Python module `plunge` (docs/cli.md, docs/plan-format.md): conversions and
// bindings only. plunge::Error becomes ValueError, plunge::InternalError
// RuntimeError, plunge::Cancelled plunge.Cancelled (an Exception: a cancel is
// not bad input);
// long calls release the GIL.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "plunge/calls.hpp"
#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/optimizer.hpp"
#include "plunge/sequencing.hpp"

namespace py = pybind11;
using nlohmann::json;

namespace {

// Python objects <-> JSON values (dicts, lists, str, int, float, bool, None).
json toJson(const py::handle& h, const std::string& where) {
  if (h.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(h)) return h.cast<bool>();
  if (py::isinstance<py::int_>(h)) return h.cast<long long>();
  if (py::isinstance<py::float_>(h)) {
    // JSON has no NaN or infinity: name the value here rather than lose it.
    const double v = h.cast<double>();
    if (!std::isfinite(v)) throw plunge::Error(where + ": not a finite number");
    return v;
  }
  if (py::isinstance<py::str>(h)) return h.cast<std::string>();
  if (py::isinstance<py::dict>(h)) {
    json out = json::object();
    for (auto item : h.cast<py::dict>()) {
      if (!py::isinstance<py::str>(item.first)) throw plunge::Error(where + ": keys must be strings");
      const std::string key = item.first.cast<std::string>();
      out[key] = toJson(item.second, where + "." + key);
    }
    return out;
  }
  if (py::isinstance<py::list>(h) || py::isinstance<py::tuple>(h)) {
    json out = json::array();
    size_t i = 0;
    for (auto item : h) out.push_back(toJson(item, where + "[" + std::to_string(i++) + "]"));
    return out;
  }
  // numpy scalars and other numbers
  if (py::hasattr(h, "__float__")) return toJson(h.attr("__float__")(), where);
  throw plunge::Error(where + ": unsupported value of type " + std::string(py::str(py::type::handle_of(h).attr("__name__"))));
}

py::object fromJson(const json& j) {
  switch (j.type()) {
    case json::value_t::object: {
      py::dict d;
      for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = fromJson(it.value());
      return d;
    }
    case json::value_t::array: {
      py::list l;
      for (const json& v : j) l.append(fromJson(v));
      return l;
    }
    case json::value_t::string: return py::str(j.get<std::string>());
    case json::value_t::boolean: return py::bool_(j.get<bool>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return py::int_(j.get<long long>());
    case json::value_t::number_float: return py::float_(j.get<double>());
    default: return py::none();
  }
}

// The plan's progress, reported on this (the calling) thread: the user's
// callable, if any, and Ctrl+C (KeyboardInterrupt) either way.
plunge::Progress progressOf(const py::object& callback) {
  return plunge::Progress([callback](double fraction, const std::string& stage) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (callback.is_none()) return true;
    const py::object go = callback(fraction, stage);
    return go.is_none() || go.cast<bool>();
  });
}

// The input's values go in and the plan's come out as Python objects: no
// JSON text on either side (calls.hpp, shared with the CLI's `call`).
py::object planDict(const py::dict& input, bool svg, const py::object& progress) {
  const json value = toJson(input, "input");
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw plunge::Error("progress: expected a callable (fraction, stage) or None");
  const plunge::Progress reporter = progressOf(progress);
  json out;
  {
    py::gil_scoped_release release;
    out = plunge::planCall(value, svg, reporter);
  }
  return fromJson(out);
}

// Each non-centre-cutting tool's start-hole drill, by id.
py::dict startHoleTools(const py::object& tools) {
  const json drills = plunge::startHoleToolsCall(toJson(tools, "tools"));
  py::dict out;
  for (auto it = drills.begin(); it != drills.end(); ++it) out[py::int_(std::stoi(it.key()))] = py::int_(it->get<int>());
  return out;
}

// The material left after `tool` moves along `moves` (rest.hpp); returns the grid's new "top".
py::object sweepPy(const py::dict& material, const py::object& tool, const py::object& moves,
                   const py::object& progress) {
  const json m = toJson(material, "material"), t = toJson(tool, "tool"), ms = toJson(moves, "moves");
  const plunge::Progress reporter = progressOf(progress);
  json out;
  {
    py::gil_scoped_release release;
    out = plunge::sweepCall(m, t, ms, reporter);
  }
  return fromJson(out["top"]);
}

std::vector<int> tourOf(const std::vector<std::pair<double, double>>& points, bool closed,
                        std::optional<std::pair<double, double>> start, const std::string& method,
                        std::uint64_t seed) {
  std::vector<plunge::Vec2> pts;
  pts.reserve(points.size());
  for (const auto& p : points) pts.push_back({p.first, p.second});
  std::optional<plunge::Vec2> s;
  if (start) s = plunge::Vec2{start->first, start->second};
  plunge::TourOptions opt;
  opt.method = plunge::tourMethodFromName(method);
  opt.seed = seed;
  py::gil_scoped_release release;
  return plunge::tour(pts, closed, s, opt);
}

py::tuple asTuple(const std::vector<double>& x) {
  py::tuple t(x.size());
  for (size_t i = 0; i < x.size(); ++i) t[i] = x[i];
  return t;
}

plunge::OptimizeResult optimizePy(const py::function& f, const std::vector<std::pair<double, double>>& bounds,
                                  const std::string& goal) {
  if (goal != "min" && goal != "max") throw plunge::Error("optimize: goal must be \"min\" or \"max\"");
  const size_t d = bounds.size();
  // The callable runs Python code: the GIL stays held.
  auto call = [&](const double* x) {
    py::object v = d == 1 ? f(x[0]) : f(x[0], x[1]);
    try {
      return v.cast<double>();
    } catch (const py::cast_error&) {
      throw plunge::Error("optimize: the function must return a float");
    }
  };
  return plunge::optimize(call, bounds, goal == "max" ? plunge::Goal::Maximize : plunge::Goal::Minimize);
}

}  // namespace

PYBIND11_MODULE(plunge, m) {
  m.doc() = "Plunge roughing planner: circle packing, gap covering, sequencing and depths";
  py::register_exception<plunge::Error>(m, "PlanError", PyExc_ValueError);
  py::register_exception<plunge::InternalError>(m, "InternalError", PyExc_RuntimeError);
  py::register_exception<plunge::Cancelled>(m, "Cancelled", PyExc_Exception);
  m.def("plan", &planDict, py::arg("input"), py::arg("svg") = false, py::arg("progress") = py::none(),
        "Plan a pocket: input and output dicts as in docs/plan-format.md; the result also "
        "holds \"summary\", the plan in one line for people (the CLI's), and with svg=True its pictures: \"svg\" the plan, "
        "\"svg_stock\" the stock left, \"svg_heights\" the stop heights (sculptured floors, or where a holder stopped plunges). progress(fraction, stage) is called "
        "about every 0.1 s while planning; returning False cancels (plunge.Cancelled, \"planning cancelled\", not a ValueError). "
        "Ctrl+C interrupts planning (KeyboardInterrupt).");
  m.def("start_hole_tools", &startHoleTools, py::arg("tools"),
        "The drill of each tool that does not cut at its centre, as the planner chooses it: "
        "{tool id: drill id} for tools given as in the input's \"tools\"; ValueError when one has none.");
  m.def("about", [] { return fromJson(plunge::aboutCall()); },
        "What this build of the planner is: {\"planner\", \"version\", \"system\", \"floors\": the floor kinds it reads}.");
  m.def("sweep", &sweepPy, py::arg("material"), py::arg("tool"), py::arg("moves"), py::arg("progress") = py::none(),
        "Rest plunging: the material's new \"top\" after the tool (as in the input's \"tools\") moves along moves "
        "[(x0, y0, z0, x1, y1, z1)] over material (as in the input's \"material\"): each cell lowered to the tool's "
        "surface over its centre.");
  py::class_<plunge::OptimizeResult>(m, "Result", "Global optimum found by plunge.optimize")
      .def_property_readonly("x", [](const plunge::OptimizeResult& r) { return asTuple(r.x); })
      .def_readonly("value", &plunge::OptimizeResult::value)
      .def_property_readonly("locals",
                             [](const plunge::OptimizeResult& r) {
                               py::list l;
                               for (const auto& o : r.locals) l.append(py::make_tuple(asTuple(o.x), o.value));
                               return l;
                             })
      .def_readonly("evaluations", &plunge::OptimizeResult::evaluations)
      .def("__repr__", [](const plunge::OptimizeResult& r) {
        return "Result(x=" + std::string(py::str(asTuple(r.x))) + ", value=" + std::to_string(r.value) + ")";
      });
  m.def("optimize", &optimizePy, py::arg("f"), py::arg("bounds"), py::arg("goal") = "min",
        "Global optimum of f(x) or f(x, y) on a box [(a, b)] or [(a, b), (c, d)] (thesis chapter 3).");
  m.def("tour", &tourOf, py::arg("points"), py::arg("closed") = true, py::arg("start") = py::none(),
        py::arg("method") = "local_search", py::arg("seed") = 0,
        "A short visiting order (permutation of range(len(points))) of 2D points; method is "
        "\"local_search\" (default) or \"annealing\" (the thesis).");
}
