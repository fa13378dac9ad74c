// plunge-rough: the command-line face of the planner (docs/plan-format.md).
// Exit 0 on success; on bad input exit 2 with one line on stderr.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>

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
  std::ofstream f(path, std::ios::binary);
  if (!f || !(f << text)) throw plunge::Error("cannot write " + path);
}

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
  CLI::App app{"Plunge roughing planner: plunge positions, order and depths for a pocket"};
  app.require_subcommand(1);
  std::string input, output = "-", svg, gcode;
  CLI::App* planCmd = app.add_subcommand("plan", "Plan the plunges of a pocket described in a JSON file");
  planCmd->add_option("INPUT", input, "plan input (JSON, see docs/plan-format.md)")->required();
  planCmd->add_option("-o,--output", output, "plan output JSON (default: standard output)");
  planCmd->add_option("--svg", svg,
                      "write the plan's pictures: the plan to this file, the stock left beside it (NAME-stock.svg) "
                      "and, over a sculptured floor, the stop heights (NAME-heights.svg)");
  planCmd->add_option("--gcode", gcode, "write RS-274 G-code (explicit moves)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "plunge-rough: error: " << e.what() << " (see --help)\n";
    return 2;
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
      for (plunge::SvgView view : plunge::svgViews(in))
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
