// wedge-dzhanibekov: writes one CSV per case of the Dzhanibekov study (docs/dzhanibekov.md):
// the 4D cuboid of figure 5 (a)-(d) and the 3D intermediate-axis flip. Columns: time, the body-frame
// angular velocity components (e01, e02, ..), kinetic energy and |L|.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>

#include "cases.hpp"

namespace {

namespace dz = wedge::dzhanibekov;

constexpr const char* kUsage =
    "usage: wedge-dzhanibekov --out DIR [--dt SECONDS] [--duration SECONDS] [--sample SECONDS]\n"
    "                         [--repair-interval STEPS] [--gyroscopic midpoint|euler]\n"
    "\n"
    "Simulates the torque-free Dzhanibekov study and writes one CSV per case into DIR:\n"
    "  4d_a.csv .. 4d_d.csv  the 4D cuboid (1.1, 0.3, 2.5, 0.7) of the paper's figure 5 (a)-(d)\n"
    "  4d_c_xyz.csv          case (c) in the xyz subspace instead of yzw (see docs/dzhanibekov.md)\n"
    "  3d_flip.csv           a 3D box (1, 2, 3) spun about its intermediate axis\n"
    "Columns: time, body-frame angular velocity components w01, w02, .. (rad/s), energy (J), L (|L|, kg m^2/s).\n"
    "\n"
    "  --out DIR           output directory (created if missing; required)\n"
    "  --dt SECONDS        time step (default 0.0001)\n"
    "  --duration SECONDS  simulated time of every case (default 60)\n"
    "  --sample SECONDS    interval between CSV rows, rounded to whole steps (default 0.01)\n"
    "  --repair-interval STEPS  steps between rotor repairs (WorldSettings::rotor_repair_interval,\n"
    "                      default 1)\n"
    "  --gyroscopic METHOD midpoint (World's default: implicit midpoint, conserves energy) or euler\n"
    "                      (the paper's implicit Euler, which slowly loses energy and |L|)\n"
    "  --help              this text\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "wedge-dzhanibekov: " << message << "\n\n" << kUsage;
  std::exit(2);
}

double parse_positive(const std::string& name, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(v) || !(v > 0.0))
    usage_error(name + " needs a positive finite number of seconds (got '" + text + "')");
  return v;
}

template <int N>
std::string component_name(int k) {
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j)
      if (wedge::Bivector<N>::index(i, j) == k) {
        std::string name = "w";  // built char by char: GCC 12 warns (-Wrestrict, a false positive) on "w" + ..
        name += char('0' + i);
        name += char('0' + j);
        return name;
      }
  return "?";
}

// Writes the CSV and prints a one-line summary: drifts of energy and |L|, and the sign changes of the
// initially dominant component.
template <int N>
void run_case(const dz::Case<N>& c, const std::filesystem::path& dir, double dt, double duration, int stride,
              int repair_interval, wedge::GyroscopicMethod method) {
  wedge::WorldSettings<N> settings;
  settings.rotor_repair_interval = repair_interval;
  settings.gyroscopic_method = method;
  const auto samples = dz::simulate<N>(c, dt, duration, stride, settings);
  const std::filesystem::path path = dir / (c.id + ".csv");
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  f << "time";
  for (int k = 0; k < wedge::kBiv<N>; ++k) f << ',' << component_name<N>(k);
  f << ",energy,L\n";
  f << std::setprecision(17);  // round-trip doubles: drifts of E and |L| are ~1e-11
  for (const auto& s : samples) {
    f << s.time;
    for (int k = 0; k < wedge::kBiv<N>; ++k) f << ',' << s.w_body[k];
    f << ',' << s.energy << ',' << s.momentum << '\n';
  }
  if (!f) throw std::runtime_error("error writing " + path.string());

  int main = 0;
  c.w0.c.cwiseAbs().maxCoeff(&main);
  int flips = 0;
  double e_dev = 0.0, l_dev = 0.0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if ((samples[i].w_body[main] > 0.0) != (samples[i - 1].w_body[main] > 0.0)) ++flips;
    e_dev = std::max(e_dev, std::abs(samples[i].energy / samples[0].energy - 1.0));
    l_dev = std::max(l_dev, std::abs(samples[i].momentum / samples[0].momentum - 1.0));
  }
  std::printf("%-8s %zu rows -> %s | sign changes of %s: %d | max |dE/E0| %.2e | max |d|L|/|L0|| %.2e\n",
              c.id.c_str(), samples.size(), path.string().c_str(), component_name<N>(main).c_str(), flips, e_dev,
              l_dev);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  double dt = 1e-4, duration = 60.0, sample = 1e-2;
  int repair_interval = 1;
  wedge::GyroscopicMethod method = wedge::WorldSettings<4>{}.gyroscopic_method;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    }
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--out") {
      out = value();
      if (out.empty()) usage_error("--out needs a directory");
    } else if (arg == "--dt") {
      dt = parse_positive(arg, value());
    } else if (arg == "--duration") {
      duration = parse_positive(arg, value());
    } else if (arg == "--sample") {
      sample = parse_positive(arg, value());
    } else if (arg == "--repair-interval") {
      const std::string text = value();
      char* end = nullptr;
      errno = 0;
      const long v = std::strtol(text.c_str(), &end, 10);
      if (text.empty() || end != text.c_str() + text.size() || errno != 0 || v < 1 || v > 2147483647L)
        usage_error("--repair-interval needs a whole number of steps >= 1 (got '" + text + "')");
      repair_interval = int(v);
    } else if (arg == "--gyroscopic") {
      const std::string text = value();
      if (text == "midpoint")
        method = wedge::GyroscopicMethod::ImplicitMidpoint;
      else if (text == "euler")
        method = wedge::GyroscopicMethod::ImplicitEuler;
      else
        usage_error("--gyroscopic needs 'midpoint' or 'euler' (got '" + text + "')");
    } else {
      usage_error("unknown argument '" + arg + "'");
    }
  }
  if (out.empty()) usage_error("--out DIR is required");
  if (dt > duration) usage_error("--dt must not exceed --duration");
  const int stride = std::max(1, int(std::lround(sample / dt)));
  std::printf("dt %g s, duration %g s, row every %d steps, gyroscopic %s, rotor repair every %d steps\n", dt, duration,
              stride, method == wedge::GyroscopicMethod::ImplicitEuler ? "implicit Euler" : "implicit midpoint",
              repair_interval);
  try {
    std::filesystem::create_directories(out);
    run_case<4>(dz::case_4d_a(), out, dt, duration, stride, repair_interval, method);
    run_case<4>(dz::case_4d_b(), out, dt, duration, stride, repair_interval, method);
    run_case<4>(dz::case_4d_c(), out, dt, duration, stride, repair_interval, method);
    run_case<4>(dz::case_4d_d(), out, dt, duration, stride, repair_interval, method);
    run_case<4>(dz::case_4d_c_xyz(), out, dt, duration, stride, repair_interval, method);
    run_case<3>(dz::case_3d_flip(), out, dt, duration, stride, repair_interval, method);
  } catch (const std::exception& e) {
    std::cerr << "wedge-dzhanibekov: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
