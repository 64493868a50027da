// `wedge replay` as a user runs it, on the shipped scenes and recordings: the hashes guard bit-identical
// replay, and each replay is also checked for what must physically or behaviourally happen (the grab
// point follows the hand, the turns reach their planes, one haptic pulse per hit, gravity within a
// stated angle, the dominoes fall, the real Quest stream stays finite and bounded). Bad input exits 2
// naming the file and the problem, with no output left behind.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>
#include <map>
#include <set>

#include "cli_runner.hpp"

using namespace cli_runner;

namespace {

const fs::path kRoot = WEDGE_SOURCE_DIR;

// The file's absolute path, quoted for the shell. (Appended piece by piece: GCC 12 wrongly warns
// -Wrestrict about "'" + std::string + "'".)
std::string path(const std::string& relative) {
  std::string quoted(1, '\'');
  quoted += (kRoot / relative).string();
  quoted += '\'';
  return quoted;
}

std::vector<json> read_lines(const fs::path& p) {
  std::vector<json> v;
  std::istringstream in(read_file(p));
  for (std::string line; std::getline(in, line);) v.push_back(json::parse(line));
  return v;
}

std::vector<double> vec(const json& j) { return j.get<std::vector<double>>(); }

// A body's state line by name.
const json& body(const json& state, const std::string& name) {
  for (const json& b : state["bodies"])
    if (b["name"] == name) return b;
  FAIL("no body " << name);
  return state;
}

// R x ~R for a 4D rotor [s, e01, e02, e03, e12, e13, e23, e0123] (the state's order), by a geometric
// product over basis-blade bitmasks written here, independent of the engine's GA code.
using Mv = std::array<double, 16>;
int reorder_sign(unsigned a, unsigned b) {
  int swaps = 0;
  for (a >>= 1; a; a >>= 1) swaps += __builtin_popcount(a & b);
  return swaps & 1 ? -1 : 1;
}
Mv gp(const Mv& x, const Mv& y) {
  Mv r{};
  for (unsigned a = 0; a < 16; ++a)
    for (unsigned b = 0; b < 16; ++b) r[a ^ b] += reorder_sign(a, b) * x[a] * y[b];
  return r;
}
std::vector<double> rotate4(const std::vector<double>& R, int axis) {
  Mv r{}, rr{}, e{};
  const unsigned blades[8] = {0, 0b0011, 0b0101, 0b1001, 0b0110, 0b1010, 0b1100, 0b1111};
  for (int k = 0; k < 8; ++k) {
    r[blades[k]] = R[k];
    const int grade = __builtin_popcount(blades[k]);
    rr[blades[k]] = (grade * (grade - 1) / 2) % 2 ? -R[k] : R[k];  // the reverse
  }
  e[1u << axis] = 1.0;
  const Mv out = gp(gp(r, e), rr);
  return {out[1], out[2], out[4], out[8]};
}

double dot4(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

struct Replay {
  Result result;
  std::vector<json> states, events;
};

Replay replay(const TempDir& dir, const std::string& scene, const std::string& recordings,
              const std::string& extra = "") {
  Replay r;
  r.result = dir.run("replay " + path(scene) + " " + recordings + " --out states.jsonl --events events.jsonl " + extra);
  if (r.result.code == 0) {
    r.states = read_lines(dir.path() / "states.jsonl");
    r.events = read_lines(dir.path() / "events.jsonl");
  }
  return r;
}

}  // namespace

// What each shipped replay must do, beside its hash: read from its events and its first and last states.
namespace {

double norm_of(const json& v) {
  double s = 0.0;
  for (const auto& x : v) s += x.get<double>() * x.get<double>();
  return std::sqrt(s);
}

const json& body_in(const json& state, const std::string& name) {
  for (const json& b : state["bodies"])
    if (b["name"] == name) return b;
  FAIL("no body " << name);
  return state;
}

int count_events(const std::vector<json>& events, const std::string& type) {
  return int(std::count_if(events.begin(), events.end(), [&](const json& e) { return e["type"] == type; }));
}

const std::vector<std::string> kToys = {"red", "blue", "cell24", "orange", "duocylinder"};

void check_replay_behaviour(const std::string& name, const Replay& r) {
  const json& first = r.states.front();
  // (--hash: the file ends with the hash line, after the last state)
  const json& last = r.states.back().contains("bodies") ? r.states.back() : r.states[r.states.size() - 2];
  // At rest: under 1 cm/s (resting bodies print exact zeros once asleep).
  auto at_rest = [&](const std::string& body) { return norm_of(body_in(last, body)["velocity"]) < 1e-2; };
  auto height = [&](const json& state, const std::string& body) { return body_in(state, body)["center"][1].get<double>(); };
  auto w_of = [&](const std::string& body) { return body_in(last, body)["center"][3].get<double>(); };
  if (name == "toy_table_grab") {
    // The hand takes the red tesseract, knocks the blue one off with it (a pulse) and throws it: both end
    // at rest on the floor (centres at their 8 cm half size); the toys it never touched stay on the table.
    CHECK(count_events(r.events, "grab") == 1);
    CHECK(count_events(r.events, "release") == 1);
    CHECK(count_events(r.events, "haptic") >= 1);
    for (const char* body : {"red", "blue"}) {
      INFO(body);
      CHECK(height(last, body) < 0.1);
      CHECK(at_rest(body));
    }
    for (const char* body : {"orange", "duocylinder"}) {
      INFO(body);
      CHECK(std::abs(height(last, body) - height(first, body)) < 5e-3);
    }
  } else if (name == "toy_table_tilt" || name == "toy_table_grab_and_tilt") {
    // The phone tilts gravity toward +w (the scene's magnitude kept): every toy slides off the table
    // that way, more than a metre into w (6 to 11 m at the end).
    CHECK(last["gravity"][3].get<double>() > 1.0);
    CHECK(std::abs(norm_of(last["gravity"]) - 9.81) < 1e-9);
    for (const std::string& body : kToys) {
      INFO(body);
      CHECK(w_of(body) > 1.0);
    }
    CHECK(count_events(r.events, "grab") == (name == "toy_table_tilt" ? 0 : 1));
  } else if (name == "dominoes_push") {
    // A push of the first domino topples all twelve: each turned past 45 degrees (rotor scalar below
    // cos 22.5 degrees), at rest.
    CHECK(count_events(r.events, "grab") == 1);
    CHECK(count_events(r.events, "haptic") >= 1);
    for (int i = 0; i < 12; ++i) {
      const std::string body = "domino" + std::to_string(i);
      INFO(body);
      CHECK(std::abs(body_in(last, body)["rotor"][0].get<double>()) < std::cos(22.5 * M_PI / 180.0));
      CHECK(at_rest(body));
    }
  } else if (name == "quest2_toy_table") {
    // The real Quest 2 session: one grab and release of a toy, gentle (nothing faster than 1 m/s);
    // every toy stays on the table within 1 cm of its height and the energy within 0.1%.
    CHECK(count_events(r.events, "grab") == 1);
    CHECK(count_events(r.events, "release") == 1);
    for (const std::string& body : kToys) {
      INFO(body);
      CHECK(std::abs(height(last, body) - height(first, body)) < 1e-2);
    }
    CHECK(std::abs(last["energy"].get<double>() / first["energy"].get<double>() - 1.0) < 1e-3);
  } else if (name == "coremotion_toy_table") {
    // A real phone held in the hand for a tremor test: gravity follows it, at the scene's magnitude,
    // mostly along +z (the phone is held flat: its accelerometer reads +1 g on z); no hand, so no
    // events; every toy slides off the table onto the floor and on along it (about 390 m in 9.4 s on
    // the endless floor, more than 10 m from the table). On the floor: over the last second each toy's
    // centre comes within 15 cm of it (the toys' half sizes are 8-10 cm; the table top is at 0.8 m).
    // The boxes slide on a face and the duocylinder rolls: they never rise 20 cm above the floor. The
    // 24-cell, at 84 m/s, hops on its vertices under gravity's floor-normal part of 2.5 m/s^2, which
    // lifts it 0.85 m for a 2 m/s vertical kick (seen: 0.95 m): it must not be thrown higher than 2 m
    // (a 3.1 m/s kick, under 4% of its speed).
    CHECK(r.events.empty());
    CHECK(std::abs(norm_of(last["gravity"]) - 9.81) < 1e-9);
    const std::size_t states = r.states.size() - (r.states.back().contains("bodies") ? 0 : 1);
    REQUIRE(states > 121);
    for (const std::string& body : kToys) {
      INFO(body);
      double lowest = 1e300, highest = -1e300;
      for (std::size_t i = states - 120; i < states; ++i) {  // the last second (120 steps)
        lowest = std::min(lowest, height(r.states[i], body));
        highest = std::max(highest, height(r.states[i], body));
      }
      CHECK(lowest < 0.15);
      CHECK(highest < (body == "cell24" ? 2.0 : 0.3));
      CHECK(norm_of(body_in(last, body)["center"]) > 10.0);
    }
  } else if (name == "chain_swing") {
    // The hand takes the chain's free end (link_11) at once and lets go at 3.05 s. While it holds, the end
    // follows the hand (its centre within 5 cm of the hand's point from 0.5 s on: the grab is a spring), and
    // the hand swings it out of the x-y plane (z > 0.5 m). Every pin holds in every state: neighbouring
    // links' centres, 0.16 m apart when joined end to end, are never more than 0.16 m + 2 mm apart (a pin's
    // gap is at least their excess). Let go, the chain is a passive system of joints and contacts: its
    // energy never rises above its value at the release (by more than 1e-4 of it: the joints' soft rows
    // hold a little energy in their stretch), and it has lost some by the end.
    CHECK(count_events(r.events, "grab") == 1);
    REQUIRE(count_events(r.events, "release") == 1);
    const json& release = *std::find_if(r.events.begin(), r.events.end(), [](const json& e) { return e["type"] == "release"; });
    CHECK(release["body"] == "link_11");
    const double t_release = release["t"].get<double>();
    double widest = 0.0, farthest_from_hand = 0.0, out_of_plane = 0.0, energy_at_release = 0.0, most_after = 0.0;
    for (const json& s : r.states) {
      if (!s.contains("bodies")) continue;
      for (int k = 0; k + 1 < 12; ++k) {
        char a[16], b[16];
        std::snprintf(a, sizeof a, "link_%02d", k);
        std::snprintf(b, sizeof b, "link_%02d", k + 1);
        const json &ca = body_in(s, a)["center"], &cb = body_in(s, b)["center"];
        double d2 = 0.0;
        for (int i = 0; i < 4; ++i) d2 += std::pow(ca[i].get<double>() - cb[i].get<double>(), 2);
        widest = std::max(widest, std::sqrt(d2));
      }
      const double t = s["time"].get<double>();
      const json& end = body_in(s, "link_11")["center"];
      if (t >= 0.5 && t < t_release) {
        const json& hand = s["hands"][1]["point"];
        double d2 = 0.0;
        for (int i = 0; i < 4; ++i) d2 += std::pow(end[i].get<double>() - hand[i].get<double>(), 2);
        farthest_from_hand = std::max(farthest_from_hand, std::sqrt(d2));
        out_of_plane = std::max(out_of_plane, end[2].get<double>());
      }
      if (t <= t_release) energy_at_release = s["energy"].get<double>();
      else most_after = std::max(most_after, s["energy"].get<double>());
    }
    const double last_energy = (r.states.back().contains("bodies") ? r.states.back() : r.states[r.states.size() - 2])["energy"];
    INFO("links " << widest << " m apart at most; the end " << farthest_from_hand << " m from the hand; energy "
                  << energy_at_release << " J at the release, " << most_after << " J at most after, " << last_energy << " J at the end");
    CHECK(widest < 0.16 + 2e-3);
    CHECK(farthest_from_hand < 0.05);
    CHECK(out_of_plane > 0.5);
    CHECK(most_after < energy_at_release * (1.0 + 1e-4));
    CHECK(last_energy < 0.97 * energy_at_release);
  } else {
    FAIL("shipped replay " << name << " has no behavioural check beside its hash: add one here");
  }
}

}  // namespace

// Every shipped recording is in at least one replay of recordings/hashes.json (written by
// tools/update_replay_hashes.sh after an intentional change); every replay reproduces its hash, gives
// the same states with two workers, and does what it must (check_replay_behaviour).
TEST_CASE("wedge replay: shipped replays reproduce their recorded state hashes", "[cli][replay][determinism]") {
  const json recorded = json::parse(read_file(kRoot / "recordings" / "hashes.json"));
  std::set<std::string> covered;
  for (const auto& [name, r] : recorded.items()) {
    INFO(name);
    std::string recs;
    for (const json& f : r["recordings"]) {
      recs += ' ';
      recs += path(f.get<std::string>());
      covered.insert(f.get<std::string>());
    }
    TempDir dir;
    const Replay run = replay(dir, r["scene"].get<std::string>(), recs, "--hash");
    REQUIRE(run.result.code == 0);
    REQUIRE(run.states.size() >= 2);
    CHECK(run.result.out.find("state hash " + r["state_hash"].get<std::string>()) != std::string::npos);
    check_replay_behaviour(name, run);
    // Two workers: the same bits in every state (WorldSettings::workers; tests/core/parallel/test_workers.cpp
    // splits large piles).
    const std::string one = read_file(dir.path() / "states.jsonl");
    const Result two =
        dir.run("replay " + path(r["scene"].get<std::string>()) + recs + " --out states2.jsonl --hash --workers 2");
    REQUIRE(two.code == 0);
    const bool same_states = read_file(dir.path() / "states2.jsonl") == one;
    CHECK(same_states);
  }
  for (const auto& e : fs::recursive_directory_iterator(kRoot / "recordings")) {
    if (e.path().extension() != ".jsonl") continue;
    const std::string rel = fs::relative(e.path(), kRoot).string();
    INFO(rel);
    CHECK(covered.count(rel) == 1);
  }
}

TEST_CASE("wedge replay: the toy table session grabs, turns into w, knocks and throws", "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/toy_table_4d.json", path("recordings/scripted/toy_table_grab.jsonl"));
  INFO(r.result.err);
  REQUIRE(r.result.code == 0);
  CHECK(r.result.out.find("1 grab, 1 release") != std::string::npos);
  // One grab of the red tesseract when the squeeze comes (t = 1.2 s), one release when it opens (5.75 s).
  std::vector<json> grabs, releases, pulses;
  for (const json& e : r.events) (e["type"] == "grab" ? grabs : e["type"] == "release" ? releases : pulses).push_back(e);
  REQUIRE(grabs.size() == 1);
  CHECK(grabs[0]["body"] == "red");
  CHECK(grabs[0]["hand"] == "right");
  CHECK(grabs[0]["t"].get<double>() == Approx(1.2).margin(0.02));
  REQUIRE(releases.size() == 1);
  CHECK(releases[0]["t"].get<double>() == Approx(5.75).margin(0.02));
  CHECK(vec(releases[0]["velocity"])[0] > 1.0);  // thrown toward +x (the hand moved at 2 m/s)
  // The grab point follows the hand: its world position from the state, against the hand's point.
  const std::vector<double> local = vec(grabs[0]["local_point"]);
  double carrying = 0.0, still = 0.0;
  for (const json& s : r.states) {
    const double t = s["time"].get<double>();
    if (s["hands"][1]["holding"] != "red") continue;
    const json& red = body(s, "red");
    // World point = position + R local ~R; the state gives the rotor, so use the centre and the
    // grab event's world point instead: the distance of the hand to the body's centre is preserved
    // by a rigid grab. |hand - centre| against |grab point - centre at the grab|.
    const std::vector<double> c = vec(red["center"]), h = vec(s["hands"][1]["point"]);
    double d2 = 0, l2 = 0;
    for (int i = 0; i < 4; ++i) d2 += (h[i] - c[i]) * (h[i] - c[i]), l2 += local[i] * local[i];
    const double gap = std::abs(std::sqrt(d2) - std::sqrt(l2));
    if (t > 1.3 && t < 4.7) carrying = std::max(carrying, gap);
    if (t > 2.7 && t < 2.8) still = std::max(still, gap);
  }
  INFO("grab point to hand: " << carrying << " m while carried and turned, " << still << " m held still");
  CHECK(carrying < 0.03);
  CHECK(still < 0.01);
  // Haptics: exactly one pulse on the right hand for the red-blue hit, and each pulse is the red one's.
  std::map<std::string, int> per_pair;
  for (const json& p : pulses) {
    CHECK(p["hand"] == "right");
    CHECK(p["bodies"][0] == "red");
    CHECK(p["amplitude"].get<double>() > 0.0);
    CHECK(p["amplitude"].get<double>() <= 1.0);
    CHECK(p["duration"].get<double>() == Approx(0.03));
    ++per_pair[p["bodies"][1].get<std::string>()];
  }
  CHECK(per_pair["blue"] == 1);
  // The blue tesseract was knocked along +x; the red one was thrown off the table's end onto the floor.
  const json& last = r.states.back();
  CHECK(vec(body(last, "blue")["center"])[0] > -0.05 + 0.1);
  CHECK(vec(body(last, "red")["center"])[1] < 0.3);
  CHECK(vec(body(last, "red")["center"])[0] > 0.8);
}

TEST_CASE("wedge replay: the held tesseract turns 90 degrees in the slice, then 60 degrees into w",
          "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/toy_table_4d.json", path("recordings/scripted/toy_table_grab.jsonl"),
                          "--until 4.2");
  REQUIRE(r.result.code == 0);
  // The body's x axis, R e0 ~R (the first column of its rotation).
  auto x_axis = [](const std::vector<double>& R) { return rotate4(R, 0); };
  auto at = [&](double t) -> const json& {
    for (const json& s : r.states)
      if (s["time"].get<double>() >= t) return s;
    return r.states.back();
  };
  const double deg = M_PI / 180;
  // After the 90 degree turn about the controller's z (t = 2.8 s, held still to 3.0 s): x -> y.
  const std::vector<double> x1 = x_axis(vec(body(at(2.95), "red")["rotor"]));
  INFO("x axis at 2.95 s: " << x1[0] << " " << x1[1] << " " << x1[2] << " " << x1[3]);
  CHECK(std::acos(std::min(1.0, dot4(x1, {0, 1, 0, 0}))) < 3 * deg);
  // After 60 degrees about the controller's x in 4D mode (its x is the world's y now): y -> toward w.
  const std::vector<double> x2 = x_axis(vec(body(at(4.15), "red")["rotor"]));
  INFO("x axis at 4.15 s: " << x2[0] << " " << x2[1] << " " << x2[2] << " " << x2[3]);
  CHECK(std::acos(std::min(1.0, dot4(x2, {0, std::cos(60 * deg), 0, std::sin(60 * deg)}))) < 3 * deg);
}

TEST_CASE("wedge replay: a phone tilts gravity by its own tilt, and toward w with the button", "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/toy_table_4d.json", path("recordings/scripted/toy_table_tilt.jsonl"));
  REQUIRE(r.result.code == 0);
  auto gravity_at = [&](double t) {
    for (const json& s : r.states)
      if (s["time"].get<double>() >= t) return vec(s["gravity"]);
    return vec(r.states.back()["gravity"]);
  };
  // Turned 30 degrees counterclockwise: gravity 30 degrees from -y toward -x, in the slice. The filter's
  // quick time constant (0.25 s, no gyro) has had 1.9 s: within 0.5 degree.
  const std::vector<double> g1 = gravity_at(3.9);
  CHECK(std::atan2(-g1[0], -g1[1]) * 180 / M_PI == Approx(30.0).margin(0.5));
  CHECK(g1[3] == 0.0);
  // With the tilt on: 15 degrees out of the slice toward +w; |g| stays 9.81.
  const std::vector<double> g2 = gravity_at(6.9);
  const double in_slice = std::sqrt(g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2]);
  CHECK(std::atan2(g2[3], in_slice) * 180 / M_PI == Approx(15.0).margin(1e-6));
  CHECK(std::sqrt(dot4(g2, g2)) == Approx(9.81).epsilon(1e-12));
  // tan 30 = 0.58 > the friction coefficient 0.5: the tesseracts slide toward -x.
  CHECK(vec(body(r.states.back(), "red")["center"])[0] < -0.45);
}

TEST_CASE("wedge replay: controllers and a phone merge by time", "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/toy_table_4d.json",
                          path("recordings/scripted/toy_table_grab.jsonl") + " " +
                              path("recordings/scripted/toy_table_tilt.jsonl"),
                          "--until 4");
  REQUIRE(r.result.code == 0);
  CHECK(r.events.at(0)["type"] == "grab");
  const std::vector<double> g = vec(r.states.back()["gravity"]);
  CHECK(std::atan2(-g[0], -g[1]) * 180 / M_PI == Approx(30.0).margin(0.5));
}

TEST_CASE("wedge replay: the dominoes are caught, turned and pushed over", "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/fig3_dominoes_4d.json", path("recordings/scripted/dominoes_push.jsonl"));
  REQUIRE(r.result.code == 0);
  REQUIRE(r.events.size() >= 2);
  CHECK(r.events[0]["type"] == "grab");
  CHECK(r.events[0]["body"] == "domino0");
  CHECK(r.events[0]["step"] == 0);
  const json& last = r.states.back();
  // An upright domino's centre is 0.6 m high; a fallen one leans on the next or lies: below 0.45 m.
  for (int i = 1; i <= 7; ++i) {
    INFO("domino" << i);
    CHECK(vec(body(last, "domino" + std::to_string(i))["center"])[1] < 0.45);
  }
}

TEST_CASE("wedge replay: the real Quest 2 stream replays finite and bounded", "[cli][replay]") {
  TempDir dir;
  const Replay r = replay(dir, "scenes/toy_table_4d.json", path("recordings/quest2/sample_movement.jsonl"),
                          "--every 12");
  INFO(r.result.err);
  REQUIRE(r.result.code == 0);  // (a non-finite state is an error, exit 2 or 3)
  CHECK(r.states.back()["time"].get<double>() == Approx(132.3).margin(0.01));  // (every 12th of 15880 steps)
  CHECK(r.result.out.find("1 grab, 1 release") != std::string::npos);  // the orange tesseract, at 34.75 s
  double fastest = 0.0, lowest = 1e9;
  for (const json& s : r.states)
    for (const json& b : s["bodies"]) {
      if (b["name"] == "floor" || b["name"] == "table") continue;
      fastest = std::max(fastest, std::sqrt(dot4(vec(b["velocity"]), vec(b["velocity"]))));
      lowest = std::min(lowest, vec(b["center"])[1]);
    }
  INFO("fastest body " << fastest << " m/s, lowest centre " << lowest << " m");
  CHECK(fastest < 20.0);  // tracking spikes reach the bodies only through the force limit
  CHECK(lowest > 0.05);   // nothing through the floor (a tesseract resting on it has its centre at 0.08)
}

TEST_CASE("wedge replay: bad recordings and misfits exit 2 naming the file, with no output", "[cli][replay]") {
  TempDir dir;
  const std::string good = read_file(kRoot / "recordings/scripted/toy_table_grab.jsonl");
  const std::string header = good.substr(0, good.find('\n') + 1);
  auto refused = [&](const std::string& name, const std::string& text, const std::string& scene,
                     const std::string& expect) {
    dir.write(name, text);
    const Result res = dir.run("replay " + path(scene) + " " + name + " --out states.jsonl --events events.jsonl");
    INFO(res.err);
    CHECK(res.code == 2);
    CHECK(res.err.find(name) != std::string::npos);
    CHECK(res.err.find(expect) != std::string::npos);
    CHECK_FALSE(fs::exists(dir.path() / "states.jsonl"));
    CHECK_FALSE(fs::exists(dir.path() / "events.jsonl"));
  };
  std::string v2 = header;
  v2.replace(v2.find("\"version\":1"), 11, "\"version\":2");
  refused("v2.jsonl", v2, "scenes/toy_table_4d.json", "version");
  refused("back.jsonl",
          header + "{\"t\":1,\"type\":\"motion\",\"acceleration\":[0,-1,0],\"tilt\":false}\n" +
              "{\"t\":0.5,\"type\":\"motion\",\"acceleration\":[0,-1,0],\"tilt\":false}\n",
          "scenes/toy_table_4d.json", ":3:");
  refused("mode4d.jsonl", good, "scenes/projectile_3d.json", "4D rotation mode");
  refused("nograv.jsonl", header + "{\"t\":0,\"type\":\"motion\",\"acceleration\":[0,-1,0],\"tilt\":false}\n",
          "scenes/free_5d.json", "no gravity");
  const Result workers = dir.run("replay " + path("scenes/toy_table_4d.json") + " x.jsonl --workers 0");
  CHECK(workers.code == 2);
  CHECK(workers.err.find("toy_table_4d.json: --workers must be an integer in 1..64") != std::string::npos);
  const Result missing = dir.run("replay " + path("scenes/toy_table_4d.json") + " nowhere.jsonl");
  CHECK(missing.code == 2);
  CHECK(missing.err.find("nowhere.jsonl") != std::string::npos);

  // A recording cut off mid-line replays every complete sample, with a warning naming the torn line.
  const std::string torn = good.substr(0, good.find('\n', good.size() / 2) + 40);
  dir.write("torn.jsonl", torn);
  const Result t = dir.run("replay " + path("scenes/toy_table_4d.json") + " torn.jsonl --out states.jsonl");
  CHECK(t.code == 0);
  CHECK(t.err.find("torn.jsonl") != std::string::npos);
  CHECK(t.err.find("torn") != std::string::npos);
}
