// plunge-rough: the command-line face of the planner (docs/plan-format.md),
// and the program the FreeCAD addon drives (`call`, docs/cli.md).
// Exit 0 on success; on bad input exit 2 with one line on stderr.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <windows.h>
#include <shellapi.h>
#endif

#include "plunge/calls.hpp"

#include "plunge/error.hpp"
#include "plunge/gcode.hpp"
#include "plunge/json.hpp"
#include "plunge/summary.hpp"
#include "plunge/svg.hpp"
#include "plunge/plan.hpp"

namespace {

void writeFile(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::cout << text;
    return;
  }
  std::ofstream f(std::filesystem::u8path(path), std::ios::binary);
  if (!f || !(f << text)) throw plunge::Error("cannot write " + path);
}

std::string readAll(const std::string& path) {
  if (path == "-") return std::string(std::istreambuf_iterator<char>(std::cin), {});
  std::ifstream f(std::filesystem::u8path(path), std::ios::binary);
  if (!f) throw plunge::Error("cannot read " + path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// `call`: one request (calls.hpp) as JSON in, its answer as JSON out, and the
// progress on stderr, one line per tick: "progress FRACTION STAGE".
int serveCall(const std::string& request, const std::string& output) {
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(readAll(request));
  } catch (const nlohmann::json::exception& e) {
    throw plunge::Error(std::string("the request is not JSON: ") + e.what());
  }
  const plunge::Progress progress([](double fraction, const std::string& stage) {
    std::fprintf(stderr, "progress %.4f %s\n", fraction, stage.c_str());
    std::fflush(stderr);
    return true;
  });
  writeFile(output, plunge::call(value, progress).dump() + "\n");
  return 0;
}

#ifdef _WIN32
// Windows hands main() its arguments in the ANSI code page: take them from the
// wide command line as UTF-8, so that a path with any character works.
std::vector<std::string> utf8Arguments() {
  int n = 0;
  wchar_t** wide = CommandLineToArgvW(GetCommandLineW(), &n);
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) {
    const int size = WideCharToMultiByte(CP_UTF8, 0, wide[i], -1, nullptr, 0, nullptr, nullptr);
    std::string arg(size > 0 ? size - 1 : 0, '\0');
    if (size > 1) WideCharToMultiByte(CP_UTF8, 0, wide[i], -1, arg.data(), size, nullptr, nullptr);
    out.push_back(std::move(arg));
  }
  LocalFree(wide);
  return out;
}
#endif

// The plan view in `path`, each other view beside it: plan.svg, plan-stock.svg.
std::string svgPath(const std::string& path, plunge::SvgView view) {
  if (view == plunge::SvgView::Plan) return path;
  const size_t dot = path.rfind('.'), slash = path.find_last_of("/\\");
  const bool ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = ext ? path.substr(0, dot) : path, suffix = ext ? path.substr(dot) : ".svg";
  return stem + "-" + plunge::svgViewName(view) + suffix;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef _WIN32
  // JSON and G-code byte for byte: no CRLF translation on the pipes.
  _setmode(_fileno(stdin), _O_BINARY);
  _setmode(_fileno(stdout), _O_BINARY);
  std::vector<std::string> args = utf8Arguments();
  std::vector<char*> pointers;
  for (std::string& a : args) pointers.push_back(a.data());
  argc = static_cast<int>(pointers.size());
  argv = pointers.data();
#endif
  CLI::App app{"Plunge roughing planner: plunge positions, order and depths for a pocket"};
  // The same options everywhere: no "/option" on Windows, where it is a path.
  app.allow_windows_style_options(false);
  app.require_subcommand(1);
  std::string input, output = "-", svg, gcode;
  CLI::App* planCmd = app.add_subcommand("plan", "Plan the plunges of a pocket described in a JSON file");
  planCmd->add_option("INPUT", input, "plan input (JSON, see docs/plan-format.md)")->required();
  planCmd->add_option("-o,--output", output, "plan output JSON (default: standard output)");
  planCmd->add_option("--svg", svg,
                      "write the plan's pictures: the plan to this file, the stock left beside it (NAME-stock.svg) "
                      "and, over a sculptured floor, the stop heights (NAME-heights.svg)");
  planCmd->add_option("--gcode", gcode, "write RS-274 G-code (explicit moves)");
  std::string request = "-";
  CLI::App* callCmd = app.add_subcommand(
      "call", "Answer one request of the FreeCAD addon (JSON in, JSON out; progress on stderr): plan, "
              "start_hole_tools, sweep or about (docs/cli.md)");
  callCmd->add_option("REQUEST", request, "the request (JSON; default: standard input)");
  callCmd->add_option("-o,--output", output, "the answer (JSON; default: standard output)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "plunge-rough: error: " << e.what() << " (see --help)\n";
    return 2;
  }
  if (*callCmd) {
    try {
      return serveCall(request, output);
    } catch (const plunge::Error& e) {
      std::cerr << "plunge-rough: error: " << e.what() << "\n";
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "plunge-rough: internal error: " << e.what() << ": please report it with the request\n";
      return 3;
    }
  }
  try {
    // A relative floor.brep is next to the input file.
    const plunge::PlanInput in = plunge::readPlanInput(input);
    const plunge::Plan plan = plunge::plan(in);
    writeFile(output, plunge::planToJson(plan));
    std::cerr << "plunge-rough: " << plunge::planSummary(plan) << "\n";
    for (const std::string& w : plan.warnings) std::cerr << "warning: " << w << "\n";
    // The reasoning of an automatic tool choice, for the user (the JSON has it
    // too); on stderr, so that the plan on stdout stays valid JSON.
    if (plan.selection)
      for (const std::string& line : plan.selection->reasoning) std::cerr << line << "\n";
    if (!svg.empty())
      for (plunge::SvgView view : plunge::svgViews(in, plan))
        writeFile(svgPath(svg, view), plunge::planToSvg(in, plan, view));
    if (!gcode.empty()) writeFile(gcode, plunge::planToGcode(in, plan));
  } catch (const plunge::Error& e) {
    std::cerr << "plunge-rough: error: " << input << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // plunge::InternalError, or anything else unforeseen: a bug
    std::cerr << "plunge-rough: internal error: " << e.what() << ": please report it with " << input << "\n";
    return 3;
  }
  return 0;
}
