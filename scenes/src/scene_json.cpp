// Scene loading: JSON -> Scene<N> -> World<N>; explicitly instantiated for N = 2..6.
// Shapes are read in shape_json.cpp. The schema is in docs/scene-format.md.
#include "wedge/scenes/scene.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <map>
#include <variant>

#include "wedge/error.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/ga/products.hpp"

namespace wedge::scenes {

namespace {

constexpr double kRotorTolerance = 1e-6;

// How far `r` is from a rotation: |R ~R - 1|, and for every basis vector e_i the size of the parts of
// R e_i ~R that are not a vector (from 5D on, R ~R = 1 alone does not make R a rotor).
template <int N>
double rotor_defect(const Rotor<N>& r) {
  double defect = (r * reverse(r) - Rotor<N>::identity()).norm();
  const Multivector<N> rm = to_multivector(r), rrev = to_multivector(reverse(r));
  for (int i = 0; i < N; ++i) {
    const Multivector<N> image = rm * to_multivector<N>(Vec<N>::Unit(i)) * rrev;
    defect = std::max(defect, (image - to_multivector<N>(vector_part(image))).norm());
  }
  return defect;
}

double read_ranged(ObjectReader& obj, const std::string& key, double fallback, double lo, double hi,
                   const char* range_text) {
  const std::optional<Node> n = obj.optional(key);
  if (!n) return fallback;
  const double v = n->number();
  if (!(v >= lo && v <= hi)) n->fail(std::string("must be ") + range_text + " (got " + n->json().dump() + ")");
  return v;
}

std::array<double, 3> read_unit_rgb(const Node& n) {
  const std::vector<double> v = n.numbers(3);
  for (double c : v)
    if (!(c >= 0.0 && c <= 1.0)) n.fail("colour components must be in [0, 1] (got " + n.json().dump() + ")");
  return {v[0], v[1], v[2]};
}

template <int N>
SceneInteraction<N> read_interaction(const Node& node) {
  ObjectReader obj(node);
  SceneInteraction<N> in;
  if (auto n = obj.optional("origin")) in.origin = n->vec<N>();
  if (auto n = obj.optional("scale")) {
    in.scale = n->number();
    if (!(in.scale > 0.0)) n->fail("must be > 0 (got " + n->json().dump() + ")");
  }
  if (auto n = obj.optional("grab_radius")) {
    in.grab_radius = n->number();
    if (!(in.grab_radius >= 0.0)) n->fail("must be >= 0 m (got " + n->json().dump() + ")");
  }
  if (auto n = obj.optional("gravity_tilt_on")) {
    in.gravity_tilt_on = n->boolean();
    if (in.gravity_tilt_on && N < 4) n->fail("the tilt turns gravity toward w, which a " + std::to_string(N) + "D scene lacks");
  }
  if (auto n = obj.optional("gravity_tilt")) {
    in.gravity_tilt = n->number();
    if (!(in.gravity_tilt >= 0.0 && in.gravity_tilt <= 90.0)) n->fail("must be in [0, 90] degrees (got " + n->json().dump() + ")");
  }
  obj.finish();
  return in;
}

SceneView read_view(const Node& node) {
  ObjectReader obj(node);
  SceneView view;
  auto point = [](const Node& n) {
    const Vec<3> p = n.vec<3>();
    return std::array<double, 3>{p[0], p[1], p[2]};
  };
  if (auto n = obj.optional("eye")) view.eye = point(*n);
  if (auto n = obj.optional("target")) view.target = point(*n);
  if (auto n = obj.optional("fov")) {
    view.fov_degrees = n->number();
    if (!(*view.fov_degrees > 0.0 && *view.fov_degrees < 180.0))
      n->fail("must be in (0, 180) degrees (got " + n->json().dump() + ")");
  }
  obj.finish();
  if (view.eye && view.target) {
    const double d2 = (*view.eye)[0] - (*view.target)[0], d1 = (*view.eye)[1] - (*view.target)[1],
                 d3 = (*view.eye)[2] - (*view.target)[2];
    if (d1 * d1 + d2 * d2 + d3 * d3 == 0.0) node.fail("\"eye\" and \"target\" must differ");
  }
  return view;
}

int read_count(ObjectReader& obj, const std::string& key, int fallback) {
  const std::optional<Node> n = obj.optional(key);
  if (!n) return fallback;
  const std::int64_t v = n->integer();
  if (v < 0 || v > 1000) n->fail("must be an integer in 0..1000 (got " + n->json().dump() + ")");
  return int(v);
}

// "contact": {..}: the fields of wedge::ContactSettings, each optional (docs/scene-format.md).
ContactSettings read_contact_settings(const Node& node) {
  ObjectReader obj(node);
  ContactSettings c;
  if (auto n = obj.optional("solver")) {
    const std::string m = n->string();
    if (m == "soft_step")
      c.solver = ContactSolver::SoftStep;
    else if (m == "paper")
      c.solver = ContactSolver::Paper;
    else
      n->fail("must be \"soft_step\" or \"paper\" (got \"" + m + "\")");
  }
  if (auto n = obj.optional("substeps")) {
    const std::int64_t v = n->integer();
    if (v < 1 || v > 64) n->fail("must be an integer in 1..64 (got " + n->json().dump() + ")");
    c.substeps = int(v);
  }
  c.contact_hertz = read_ranged(obj, "contact_hertz", c.contact_hertz, 0.0, 1e6, ">= 0 Hz");
  c.contact_damping_ratio = read_ranged(obj, "contact_damping_ratio", c.contact_damping_ratio, 0.0, 1e6, ">= 0");
  c.contact_push_speed = read_ranged(obj, "contact_push_speed", c.contact_push_speed, 0.0, 1e6, ">= 0 m/s");
  c.joint_hertz = read_ranged(obj, "joint_hertz", c.joint_hertz, 0.0, 1e6, ">= 0 Hz");
  c.joint_damping_ratio = read_ranged(obj, "joint_damping_ratio", c.joint_damping_ratio, 0.0, 1e6, ">= 0");
  c.joint_angular_hertz = read_ranged(obj, "joint_angular_hertz", c.joint_angular_hertz, 0.0, 1e6, ">= 0 Hz");
  c.restitution_threshold = read_ranged(obj, "restitution_threshold", c.restitution_threshold, 0.0, 1e6, ">= 0 m/s");
  c.recycle_distance = read_ranged(obj, "recycle_distance", c.recycle_distance, 0.0, 1e3, "in [0, 1000] m");
  c.recycle_angle = read_ranged(obj, "recycle_angle", c.recycle_angle, 0.0, 3.2, "in [0, 3.2] rad");
  c.contact_margin = read_ranged(obj, "contact_margin", c.contact_margin, 0.0, 1e3, "in [0, 1000] m");
  c.face_preference = read_ranged(obj, "face_preference", c.face_preference, 0.0, 1e3, "in [0, 1000] m");
  c.static_slip_speed = read_ranged(obj, "static_slip_speed", c.static_slip_speed, 0.0, 1e6, ">= 0 m/s");
  c.collision_iterations = read_count(obj, "collision_iterations", c.collision_iterations);
  c.contact_iterations = read_count(obj, "contact_iterations", c.contact_iterations);
  c.warm_start = obj.boolean_or("warm_start", c.warm_start);
  c.contact_tolerance = read_ranged(obj, "contact_tolerance", c.contact_tolerance, 0.0, 1e6, ">= 0 m/s");
  c.shock_iterations = read_count(obj, "shock_iterations", c.shock_iterations);
  c.shock_tolerance = read_ranged(obj, "shock_tolerance", c.shock_tolerance, 0.0, 1e6, ">= 0 m/s");
  c.linear_slop = read_ranged(obj, "linear_slop", c.linear_slop, 0.0, 1e3, "in [0, 1000] m");
  c.position_correction = read_ranged(obj, "position_correction", c.position_correction, 1e-9, 1.0, "in (0, 1]");
  c.position_iterations = read_count(obj, "position_iterations", c.position_iterations);
  c.continuous = obj.boolean_or("continuous", c.continuous);
  c.continuous_gap = read_ranged(obj, "continuous_gap", c.continuous_gap, 0.0, 1e3, "in [0, 1000] m");
  c.max_turn = read_ranged(obj, "max_turn", c.max_turn, 1e-9, 1e3, "in (0, 1000] rad per step");
  c.allow_sleep = obj.boolean_or("allow_sleep", c.allow_sleep);
  c.sleep_linear_speed = read_ranged(obj, "sleep_linear_speed", c.sleep_linear_speed, 0.0, 1e6, ">= 0 m/s");
  c.time_to_sleep = read_ranged(obj, "time_to_sleep", c.time_to_sleep, 0.0, 1e9, ">= 0 s");
  obj.finish();
  return c;
}

template <int N>
SceneBody<N> read_body(const Node& node, int index) {
  ObjectReader obj(node);
  BodyDef<N> def;
  Material material;

  def.name = "body" + std::to_string(index);
  if (auto n = obj.optional("name")) {
    def.name = n->string();
    if (def.name.empty()) n->fail("must not be empty");
  }

  const bool is_static = obj.boolean_or("static", false);
  const bool is_kinematic = obj.boolean_or("kinematic", false);
  if (is_static && is_kinematic) node.fail("a body cannot be both \"static\" and \"kinematic\"");
  def.type = is_static ? BodyType::Static : is_kinematic ? BodyType::Kinematic : BodyType::Dynamic;

  const Node shape_node = obj.required("shape");
  Shape<N> shape = read_shape<N>(shape_node);
  const bool halfspace = !shape.bounded();
  if (halfspace && !is_static)
    shape_node.fail("a halfspace is infinite and has no mass: its body must be \"static\": true");

  if (auto n = obj.optional("position")) def.position = n->vec<N>();
  if (auto n = obj.optional("rotor")) {
    def.rotor = n->coeffs<Rotor<N>>();
    const double defect = rotor_defect(def.rotor);
    if (!(defect <= kRotorTolerance))
      n->fail("not a rotation: R ~R differs from 1 (or R x ~R from a vector) by " + format_number(defect) +
              " (tolerance 1e-6); components are (1, e01, e02, .., e12, .., e0123, ..)");
  }
  if (auto n = obj.optional("velocity")) def.velocity = n->vec<N>();
  if (auto n = obj.optional("angular_velocity")) def.angular_velocity = n->coeffs<Bivector<N>>();
  def.linear_drag = read_ranged(obj, "linear_drag", 0.0, 0.0, HUGE_VAL, ">= 0");
  def.angular_drag = read_ranged(obj, "angular_drag", 0.0, 0.0, HUGE_VAL, ">= 0");

  material.restitution = read_ranged(obj, "restitution", 0.0, 0.0, 1.0, "in [0, 1]");
  material.friction = read_ranged(obj, "friction", 0.5, 0.0, HUGE_VAL, ">= 0");
  material.kinetic_friction = read_ranged(obj, "kinetic_friction", 0.4, 0.0, HUGE_VAL, ">= 0");

  std::optional<std::array<double, 3>> color;
  if (auto n = obj.optional("color")) color = read_unit_rgb(*n);

  const std::optional<Node> density_node = obj.optional("density");
  const std::optional<Node> mass_node = obj.optional("mass");
  obj.finish();

  if (halfspace) {
    if (density_node || mass_node)
      (density_node ? *density_node : *mass_node).fail("a halfspace is infinite and has no mass or density");
    // local_center 0: the body frame is the halfspace's frame.
    return SceneBody<N>{std::move(def), std::move(shape), 0.0, std::nullopt, material, color};
  }
  if (density_node && mass_node) mass_node->fail("give either \"density\" or \"mass\", not both");
  double density = 1.0;
  if (density_node) {
    density = density_node->number();
    if (!(density > 0.0)) density_node->fail("must be > 0 (got " + density_node->json().dump() + ")");
  }
  MassProperties<N> mp;
  try {
    mp = mass_properties<N>(shape, density);
    if (mass_node) {
      const double m = mass_node->number();
      if (!(m > 0.0)) mass_node->fail("must be > 0 (got " + mass_node->json().dump() + ")");
      mp = with_mass<N>(mp, m);
      density = m / mp.volume;
    }
  } catch (const Error& e) {
    throw JsonError(shape_node.path(), e.what());
  }
  if (!(mp.mass > 0.0) || !std::isfinite(mp.mass) || !std::isfinite(density) || !all_finite(mp.inertia) ||
      !all_finite(mp.center))
    shape_node.fail("mass properties are not positive and finite (mass " + format_number(mp.mass) +
                    "); is the shape degenerate or the density extreme?");
  def.mass = mp.mass;
  def.local_center = mp.center;
  def.inertia = mp.inertia;
  return SceneBody<N>{std::move(def), std::move(shape), density, mp, material, color};
}

// A body of a joint, by name.
std::uint32_t joint_body(const Node& node, const std::map<std::string, std::uint32_t>& index) {
  const std::string name = node.string();
  const auto it = index.find(name);
  if (it == index.end()) node.fail("no body is named \"" + name + "\"");
  return it->second;
}

// An anchor must lie on or near its body: within its shape's box grown by the box's half-diagonal
// (an anchor metres off a 10 cm link is a typo, and would make a lever of it). Halfspaces: anywhere.
template <int N>
void check_anchor(const Node& node, const Vec<N>& anchor, const SceneBody<N>& body) {
  if (!body.shape.bounded()) return;
  const Aabb<N> box = world_aabb(body.shape, Vec<N>(Vec<N>::Zero()), Rotor<N>::identity());
  const Vec<N> half = 0.5 * (box.hi - box.lo);
  const Vec<N> outside = (anchor - 0.5 * (box.hi + box.lo)).cwiseAbs() - half;
  const double distance = outside.cwiseMax(0.0).norm();
  if (distance > half.norm())
    node.fail("is " + format_number(distance) + " m outside body \"" + body.def.name + "\" (whose box has half-diagonal " +
              format_number(half.norm()) + " m): an anchor lies on or near its body, in the body's frame");
}

// A pair of limits, lower <= upper, each finite (|x| <= 1e6); the upper defaults to 0.
void read_limits(ObjectReader& obj, const Node& node, const std::string& lower_key, const std::string& upper_key,
                 const std::string& unit, double& lower, double& upper) {
  lower = read_ranged(obj, lower_key, 0.0, -1e6, 1e6, ("finite, in " + unit).c_str());
  const std::optional<Node> upper_node = obj.optional(upper_key);
  if (upper_node) {
    upper = upper_node->number();
    if (!(upper >= lower && upper <= 1e6))
      upper_node->fail("must be >= " + lower_key + " (" + format_number(lower) + " " + unit + ") (got " +
                       upper_node->json().dump() + ")");
  } else if (lower > 0.0) {
    node.fail(lower_key + " is above the default " + upper_key + " 0: give " + upper_key);
  }
}

template <int N>
RevoluteJointDef<N> read_revolute(ObjectReader& obj, const Node& node, const JointBodies<N>& jb) {
  RevoluteJointDef<N> r{jb};
  const auto plane = [&](const char* key, Vec<N>& u, Vec<N>& v) {
    const std::optional<Node> n = obj.optional(key);
    if (!n) return;
    const std::vector<Node> uv = n->array();
    if (uv.size() != 2) n->fail("must be two vectors, u and v (got " + std::to_string(uv.size()) + ")");
    u = uv[0].vec<N>();
    v = uv[1].vec<N>();
  };
  plane("plane_a", r.plane_u_a, r.plane_v_a);
  plane("plane_b", r.plane_u_b, r.plane_v_b);
  r.limit = obj.boolean_or("limit", false);
  read_limits(obj, node, "lower_angle", "upper_angle", "rad", r.lower_angle, r.upper_angle);
  r.motor = obj.boolean_or("motor", false);
  r.motor_speed = read_ranged(obj, "motor_speed", 0.0, -1e6, 1e6, "a finite speed in rad/s");
  r.max_motor_torque = read_ranged(obj, "max_motor_torque", 0.0, 0.0, HUGE_VAL, ">= 0 N m");
  return r;
}

// The axis is a direction in body_a's frame (or the world's), any length but zero: it is normalised.
template <int N>
PrismaticJointDef<N> read_prismatic(ObjectReader& obj, const Node& node, const JointBodies<N>& jb) {
  PrismaticJointDef<N> p{jb};
  if (auto n = obj.optional("axis")) {
    const Vec<N> axis = n->vec<N>();
    if (!(axis.norm() > 1e-9)) n->fail("must be a direction, not zero (got " + n->json().dump() + ")");
    p.axis_a = axis.normalized();
  }
  p.limit = obj.boolean_or("limit", false);
  read_limits(obj, node, "lower_translation", "upper_translation", "m", p.lower_translation, p.upper_translation);
  p.motor = obj.boolean_or("motor", false);
  p.motor_speed = read_ranged(obj, "motor_speed", 0.0, -1e6, 1e6, "a finite speed in m/s");
  p.max_motor_force = read_ranged(obj, "max_motor_force", 0.0, 0.0, HUGE_VAL, ">= 0 N");
  return p;
}

template <int N>
DistanceJointDef<N> read_distance(ObjectReader& obj, const Node& node, const JointBodies<N>& jb) {
  DistanceJointDef<N> d{jb};
  d.spring = obj.boolean_or("spring", false);
  d.length = d.spring ? read_ranged(obj, "length", -1.0, 0.0, HUGE_VAL, ">= 0 m (leave it out for the anchors' distance)")
                      : read_ranged(obj, "length", -1.0, 1e-4, HUGE_VAL,
                                    ">= 0.0001 m (leave it out for the anchors' distance)");
  d.frequency = read_ranged(obj, "frequency", 0.0, 0.0, 1e6, ">= 0 Hz");
  d.damping_ratio = read_ranged(obj, "damping_ratio", 0.0, 0.0, 1e6, ">= 0");
  d.min_length = read_ranged(obj, "min_length", 0.0, 0.0, HUGE_VAL, ">= 0 m");
  const std::optional<Node> max_node = obj.optional("max_length");
  if (max_node) {
    d.max_length = max_node->number();
    if (!(d.max_length >= d.min_length))
      max_node->fail("must be >= min_length (" + format_number(d.min_length) + " m) (got " + max_node->json().dump() + ")");
  }
  if (!d.spring && (d.frequency != 0.0 || d.min_length != 0.0 || max_node))
    node.fail("frequency, damping_ratio, min_length and max_length are a spring's: add \"spring\": true");
  return d;
}

// One entry of `joints`: the bodies and anchors every joint has, then its type's own keys.
template <int N>
SceneJoint<N> read_joint(const Node& node, const std::map<std::string, std::uint32_t>& index,
                         const std::vector<SceneBody<N>>& bodies) {
  ObjectReader obj(node);
  const Node type_node = obj.required("type");
  const std::string type = type_node.string();
  JointBodies<N> jb;
  if (auto n = obj.optional("body_a")) jb.body_a = BodyId{joint_body(*n, index)};  // absent: the world
  const Node body_b = obj.required("body_b");
  jb.body_b = BodyId{joint_body(body_b, index)};
  if (auto n = obj.optional("anchor_a")) {
    jb.anchor_a = n->vec<N>();
    if (jb.body_a) check_anchor<N>(*n, jb.anchor_a, bodies[jb.body_a->index]);
  }
  if (auto n = obj.optional("anchor_b")) {
    jb.anchor_b = n->vec<N>();
    check_anchor<N>(*n, jb.anchor_b, bodies[jb.body_b.index]);
  }
  jb.collide_connected = obj.boolean_or("collide_connected", false);
  SceneJoint<N> joint;
  if (type == "point") {
    joint = PointJointDef<N>{jb};
  } else if (type == "distance") {
    joint = read_distance<N>(obj, node, jb);
  } else if (type == "revolute") {
    joint = read_revolute<N>(obj, node, jb);
  } else if (type == "prismatic") {
    joint = read_prismatic<N>(obj, node, jb);
  } else if (type == "weld") {
    WeldJointDef<N> w{jb};
    w.frequency = read_ranged(obj, "frequency", 0.0, 0.0, 1e6, ">= 0 Hz (0: rigid)");
    w.damping_ratio = read_ranged(obj, "damping_ratio", 1.0, 0.0, 1e6, ">= 0");
    joint = w;
  } else {
    type_node.fail("must be \"point\", \"distance\", \"revolute\", \"prismatic\" or \"weld\" (got \"" + type + "\")");
  }
  obj.finish();
  return joint;
}

}  // namespace

int read_dim(const Json& doc, const std::string& file) {
  return with_file_context(file, "", [&] {
    const Node root(doc, "");
    if (!doc.is_object()) root.fail("expected a JSON object at the top level, got " + root.describe_type());
    const auto it = doc.find("dim");
    if (it == doc.end()) root.fail("missing key \"dim\" (the dimension, 2..6)");
    const Node dim(*it, "dim");
    const std::int64_t n = dim.integer();
    if (n < kMinDim || n > kMaxDim) dim.fail("must be 2, 3, 4, 5 or 6 (got " + std::to_string(n) + ")");
    return int(n);
  });
}

template <int N>
Scene<N> load_scene(const Json& doc, const std::string& file) {
  return with_file_context(file, "", [&] {
    Scene<N> scene;
    ObjectReader obj(Node(doc, ""));
    obj.required("dim");  // read_dim checked it
    if (auto n = obj.optional("description")) n->string();
    if (auto n = obj.optional("gravity")) scene.settings.gravity = n->vec<N>();
    if (auto n = obj.optional("timestep")) {
      scene.timestep = n->number();
      if (!(scene.timestep >= kMinTimestep && scene.timestep <= kMaxTimestep))
        n->fail("must be in [1e-6, 0.1] s (got " + n->json().dump() + ")");
    }
    scene.settings.gyroscopic = obj.boolean_or("gyroscopic", true);
    if (auto n = obj.optional("gyroscopic_method")) {
      const std::string m = n->string();
      if (m == "midpoint")
        scene.settings.gyroscopic_method = GyroscopicMethod::ImplicitMidpoint;
      else if (m == "euler")
        scene.settings.gyroscopic_method = GyroscopicMethod::ImplicitEuler;
      else
        n->fail("must be \"midpoint\" or \"euler\" (got \"" + m + "\")");
    }
    if (auto n = obj.optional("rotor_repair_interval")) {
      const std::int64_t r = n->integer();
      if (r < 1 || r > 1'000'000'000) n->fail("must be an integer >= 1 (got " + n->json().dump() + ")");
      scene.settings.rotor_repair_interval = int(r);
    }
    if (auto n = obj.optional("contact")) scene.settings.contact = read_contact_settings(*n);
    if (auto n = obj.optional("view")) scene.view = read_view(*n);
    if (auto n = obj.optional("interaction")) scene.interaction = read_interaction<N>(*n);
    const Node bodies = obj.required("bodies");
    const std::optional<Node> joints = obj.optional("joints");
    obj.finish();

    std::map<std::string, std::uint32_t> names;
    const std::vector<Node> list = bodies.array();
    for (std::size_t i = 0; i < list.size(); ++i) {
      scene.bodies.push_back(read_body<N>(list[i], int(i)));
      const std::string& name = scene.bodies.back().def.name;
      if (!names.emplace(name, std::uint32_t(i)).second) list[i].fail("duplicate body name \"" + name + "\"");
    }
    if (joints) {
      if (scene.settings.contact.solver == ContactSolver::Paper)
        joints->fail("the paper's contact solver (contact.solver \"paper\") has no joints");
      for (const Node& j : joints->array()) scene.joints.push_back(read_joint<N>(j, names, scene.bodies));
    }
    return scene;
  });
}

template <int N>
World<N> Scene<N>::make_world(const std::string& file) const {
  World<N> world = with_file_context(file, "", [&] { return World<N>(settings); });
  for (std::size_t i = 0; i < bodies.size(); ++i)
    with_file_context(file, index_path("bodies", i), [&] {
      BodyDef<N> def = bodies[i].def;
      def.shape = std::make_shared<const Shape<N>>(bodies[i].shape);
      def.material = bodies[i].material;
      world.add_body(def);
    });
  for (std::size_t i = 0; i < joints.size(); ++i)
    with_file_context(file, index_path("joints", i),
                      [&] { std::visit([&](const auto& def) { world.add_joint(def); }, joints[i]); });
  return world;
}

#define WEDGE_CLI_INSTANTIATE(N)                                              \
  template Scene<N> load_scene<N>(const Json&, const std::string&);          \
  template struct Scene<N>;
WEDGE_CLI_INSTANTIATE(2)
WEDGE_CLI_INSTANTIATE(3)
WEDGE_CLI_INSTANTIATE(4)
WEDGE_CLI_INSTANTIATE(5)
WEDGE_CLI_INSTANTIATE(6)
#undef WEDGE_CLI_INSTANTIATE

}  // namespace wedge::scenes
