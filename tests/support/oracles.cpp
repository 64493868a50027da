#include "oracles.hpp"

#include "dense.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>

#include <glpk.h>

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

// Qhull's C headers last: they define many macros.
#include <libqhull_r/qhull_ra.h>

namespace wedge::oracle {

// ---- (a) GLPK --------------------------------------------------------------------------------------

LpSeparation lp_separation(const Points& a, const Points& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("lp_separation: empty point set");
  const int n = int(a[0].size()), na = int(a.size()), nb = int(b.size());
  glp_term_out(GLP_OFF);
  std::unique_ptr<glp_prob, void (*)(glp_prob*)> lp(glp_create_prob(), glp_delete_prob);
  glp_prob* p = lp.get();
  glp_set_obj_dir(p, GLP_MIN);
  // Columns 1..na: lambda, na+1..na+nb: mu, na+nb+1: t; all >= 0.
  const int ncols = na + nb + 1, t_col = ncols;
  glp_add_cols(p, ncols);
  for (int c = 1; c <= ncols; ++c) glp_set_col_bnds(p, c, GLP_LO, 0.0, 0.0);
  glp_set_obj_coef(p, t_col, 1.0);
  // Rows 1, 2: sum lambda = 1, sum mu = 1; 3 + 2k: A_k - B_k - t <= 0; 4 + 2k: A_k - B_k + t >= 0.
  const int nrows = 2 + 2 * n;
  glp_add_rows(p, nrows);
  glp_set_row_bnds(p, 1, GLP_FX, 1.0, 1.0);
  glp_set_row_bnds(p, 2, GLP_FX, 1.0, 1.0);
  for (int k = 0; k < n; ++k) {
    glp_set_row_bnds(p, 3 + 2 * k, GLP_UP, 0.0, 0.0);
    glp_set_row_bnds(p, 4 + 2 * k, GLP_LO, 0.0, 0.0);
  }
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  auto put = [&](int r, int c, double v) {
    ia.push_back(r);
    ja.push_back(c);
    ar.push_back(v);
  };
  for (int i = 0; i < na; ++i) put(1, 1 + i, 1.0);
  for (int j = 0; j < nb; ++j) put(2, 1 + na + j, 1.0);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < na; ++i) {
      put(3 + 2 * k, 1 + i, a[std::size_t(i)][k]);
      put(4 + 2 * k, 1 + i, a[std::size_t(i)][k]);
    }
    for (int j = 0; j < nb; ++j) {
      put(3 + 2 * k, 1 + na + j, -b[std::size_t(j)][k]);
      put(4 + 2 * k, 1 + na + j, -b[std::size_t(j)][k]);
    }
    put(3 + 2 * k, t_col, -1.0);
    put(4 + 2 * k, t_col, 1.0);
  }
  glp_load_matrix(p, int(ia.size()) - 1, ia.data(), ja.data(), ar.data());

  // GLPK's default primal feasibility tolerance (1e-7) would let a gap below 1e-7 pass as t = 0; the
  // data are of order 1 and the LPs small, so a much tighter one is tried first. On near-degenerate
  // LPs (gaps below about 1e-9) it can fail to find any feasible basis; then looser ones are tried.
  LpSeparation out;
  int code = 0;
  for (const double tol : {1e-12, 1e-10, 1e-7}) {
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_OFF;
    parm.tol_bnd = tol;
    glp_std_basis(p);
    code = glp_simplex(p, &parm);
    out.feasibility_tolerance = tol;
    if (code == 0 && glp_get_status(p) == GLP_OPT) break;
  }
  if (code != 0) {
    out.status = "GLPK returned error code " + std::to_string(code);
    return out;
  }
  if (glp_get_status(p) != GLP_OPT) {
    out.status = "GLPK status " + std::to_string(glp_get_status(p)) + " (not optimal)";
    return out;
  }
  out.optimal = true;
  out.status = "optimal";
  out.distance = glp_get_col_prim(p, t_col);
  out.point_a = Point::Zero(n);
  out.point_b = Point::Zero(n);
  for (int i = 0; i < na; ++i) out.point_a += glp_get_col_prim(p, 1 + i) * a[std::size_t(i)];
  for (int j = 0; j < nb; ++j) out.point_b += glp_get_col_prim(p, 1 + na + j) * b[std::size_t(j)];
  return out;
}

// ---- Qhull -----------------------------------------------------------------------------------------

Hull qhull(const Points& points) {
  if (points.empty()) throw std::runtime_error("qhull: no points");
  const int dim = int(points[0].size()), count = int(points.size());
  std::vector<double> coords(std::size_t(dim) * std::size_t(count));
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < dim; ++k) coords[std::size_t(i * dim + k)] = points[std::size_t(i)][k];
  char* buf = nullptr;
  std::size_t len = 0;
  FILE* err = open_memstream(&buf, &len);
  auto qh_storage = std::make_unique<qhT>();
  qhT* qh = qh_storage.get();
  QHULL_LIB_CHECK
  qh_zero(qh, err);
  char cmd[] = "qhull";  // default options: coplanar facets merged
  const int code = qh_new_qhull(qh, dim, count, coords.data(), False, cmd, nullptr, err);
  Hull hull;
  hull.dim = dim;
  if (code == 0) {
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
      HullFacet f;
      FOREACHvertex_(facet->vertices) f.vertices.push_back(qh_pointid(qh, vertex->point));
      std::sort(f.vertices.begin(), f.vertices.end());
      f.normal = Eigen::Map<const Eigen::VectorXd>(facet->normal, dim);
      f.offset = -facet->offset;  // Qhull: normal . x + offset <= 0 inside
      hull.facets.push_back(std::move(f));
    }
    FORALLvertices hull.vertices.push_back(qh_pointid(qh, vertex->point));
    std::sort(hull.vertices.begin(), hull.vertices.end());
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  const std::string message = buf ? std::string(buf, len) : std::string();
  std::free(buf);
  if (code != 0) throw std::runtime_error("qhull failed (" + std::to_string(code) + "): " + message.substr(0, 300));
  return hull;
}

// ---- (c) Brute-force closest point -------------------------------------------------------------------

namespace {

// The projection of p onto the affine hull of the given points, and that hull's dimension.
std::pair<Point, int> project_affine(const Points& v, const std::vector<int>& face, const Point& p) {
  const Point& v0 = v[std::size_t(face[0])];
  if (face.size() == 1) return {v0, 0};
  Eigen::MatrixXd m(v0.size(), Eigen::Index(face.size() - 1));
  for (std::size_t i = 1; i < face.size(); ++i) m.col(Eigen::Index(i - 1)) = v[std::size_t(face[i])] - v0;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(m);
  cod.setThreshold(1e-10);
  const Eigen::VectorXd x = cod.solve(p - v0);  // a least-squares solution: m x is the projection
  return {v0 + m * x, int(cod.rank())};
}

ClosestPoint closest_point_on_hull(const Points& vertices, const Hull& hull, const Point& p) {
  double scale = 1.0;
  for (const Point& v : vertices) scale = std::max(scale, v.norm());
  const double band = 1e-9 * scale;

  ClosestPoint out;
  double worst = -INFINITY;  // max_f normal_f . p - offset_f
  double nearest = INFINITY;
  std::size_t nearest_facet = 0;
  for (std::size_t f = 0; f < hull.facets.size(); ++f) {
    const double s = hull.facets[f].normal.dot(p) - hull.facets[f].offset;
    worst = std::max(worst, s);
    if (-s < nearest) {
      nearest = -s;
      nearest_facet = f;
    }
  }
  if (worst <= 0.0) {
    out.inside = true;
    out.point = p;
    out.distance = 0.0;
    out.face_dim = hull.dim;
    out.face = hull.vertices;
    out.boundary_distance = nearest;
    out.boundary_normal = hull.facets[nearest_facet].normal;
    out.boundary_point = p + nearest * out.boundary_normal;
    return out;
  }

  // Faces inside facets that p sees (normal . p > offset): the closest point lies in one of them.
  std::set<std::vector<int>> faces;
  std::vector<std::vector<int>> queue;
  for (const HullFacet& f : hull.facets)
    if (f.normal.dot(p) > f.offset && faces.insert(f.vertices).second) queue.push_back(f.vertices);
  while (!queue.empty()) {
    const std::vector<int> face = std::move(queue.back());
    queue.pop_back();
    for (const HullFacet& f : hull.facets) {
      std::vector<int> t;
      std::set_intersection(face.begin(), face.end(), f.vertices.begin(), f.vertices.end(), std::back_inserter(t));
      if (!t.empty() && faces.insert(t).second) queue.push_back(std::move(t));
    }
  }
  // Single vertices of those faces (a vertex is a face even where no two facets meet in just it).
  std::set<int> used;
  for (const std::vector<int>& f : faces) used.insert(f.begin(), f.end());
  for (int v : used) faces.insert({v});

  out.distance = INFINITY;
  for (const std::vector<int>& face : faces) {
    ++out.faces_tried;
    const auto [q, dim] = project_affine(vertices, face, p);
    bool in = true;
    for (const HullFacet& f : hull.facets)
      if (f.normal.dot(q) > f.offset + band) {
        in = false;
        break;
      }
    if (!in) continue;
    const double d = (p - q).norm();
    // Ties (the same point reached from a face and its sub-faces): keep the lowest-dimensional face.
    if (d < out.distance - 1e-12 * scale || (d <= out.distance + 1e-12 * scale && dim < out.face_dim)) {
      out.distance = d;
      out.point = q;
      out.face_dim = dim;
      out.face = face;
    }
  }
  if (!std::isfinite(out.distance)) throw std::runtime_error("closest_point_brute_force: no face accepted a projection");
  out.boundary_point = out.point;
  out.boundary_normal = (p - out.point) / out.distance;
  return out;
}

}  // namespace

ClosestPoint closest_point_brute_force(const Points& vertices, const Point& p) {
  return closest_point_on_hull(vertices, qhull(vertices), p);
}

// ---- (b) Minkowski difference ------------------------------------------------------------------------

MinkowskiMtd minkowski_mtd(const Points& a, const Points& b, double tie_tolerance) {
  Points diff;
  diff.reserve(a.size() * b.size());
  for (const Point& x : a)
    for (const Point& y : b) diff.push_back(x - y);
  const Hull hull = qhull(diff);
  const int n = hull.dim;
  MinkowskiMtd out;
  out.minkowski_facets = int(hull.facets.size());
  std::size_t nearest = 0;
  for (std::size_t f = 1; f < hull.facets.size(); ++f)
    if (hull.facets[f].offset < hull.facets[nearest].offset) nearest = f;
  const double min_offset = hull.facets[nearest].offset;
  if (min_offset >= 0.0) {
    // The origin is inside A - B: translating B by t separates iff t is outside A - B, and the shortest
    // such t reaches the nearest facet: t = offset_f * normal_f. B moves along +normal: from A to B.
    out.intersecting = true;
    out.depth = min_offset;
    out.normal = hull.facets[nearest].normal;
    for (const HullFacet& f : hull.facets)
      if (f.offset <= min_offset + tie_tolerance) out.tied_normals.push_back(f.normal);
    return out;
  }
  const ClosestPoint c = closest_point_on_hull(diff, hull, Point::Zero(n));
  out.depth = -c.distance;
  out.normal = -c.point / c.distance;  // q = a - b, so b - a = -q points from A to B
  out.tied_normals = {out.normal};
  return out;
}

// ---- (d) Bullet -------------------------------------------------------------------------------------

namespace {

btTransform to_bullet(const Eigen::Vector3d& pos, const Eigen::Matrix3d& rot) {
  const btMatrix3x3 basis(rot(0, 0), rot(0, 1), rot(0, 2), rot(1, 0), rot(1, 1), rot(1, 2), rot(2, 0), rot(2, 1),
                          rot(2, 2));
  return btTransform(basis, btVector3(pos[0], pos[1], pos[2]));
}

Eigen::Vector3d from_bullet(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

// Bullet reports normalOnBInWorld pointing from B towards A, the point on B, and depth < 0 when the
// shapes overlap (btManifoldResult: point on A = point on B + normal * depth).
struct Collector : btDiscreteCollisionDetectorInterface::Result {
  std::vector<Eigen::Vector3d> normals, points;
  std::vector<double> depths;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3& normal_on_b, const btVector3& point, btScalar depth) override {
    normals.push_back(from_bullet(normal_on_b));
    points.push_back(from_bullet(point));
    depths.push_back(double(depth));
  }
};

}  // namespace

BulletBoxBox bullet_box_box(const Eigen::Vector3d& half_a, const Eigen::Vector3d& pos_a, const Eigen::Matrix3d& rot_a,
                            const Eigen::Vector3d& half_b, const Eigen::Vector3d& pos_b, const Eigen::Matrix3d& rot_b) {
  static_assert(sizeof(btScalar) == sizeof(double), "link Bullet in double precision (bullet-float64)");
  btBoxShape box_a(btVector3(half_a[0], half_a[1], half_a[2]));
  btBoxShape box_b(btVector3(half_b[0], half_b[1], half_b[2]));
  // btBoxShape::setMargin keeps the outer extents: with margin 0 the implicit shape is the full box.
  box_a.setMargin(0.0);
  box_b.setMargin(0.0);
  btDiscreteCollisionDetectorInterface::ClosestPointInput input;
  input.m_transformA = to_bullet(pos_a, rot_a);
  input.m_transformB = to_bullet(pos_b, rot_b);

  BulletBoxBox out;
  {
    btBoxBoxDetector detector(&box_a, &box_b);
    Collector c;
    detector.getClosestPoints(input, c, nullptr);
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      out.intersecting = true;
      out.normal = -c.normals[i];  // all points share it
      out.contact_points.push_back(c.points[i]);
      out.contact_depths.push_back(-c.depths[i]);
      out.contact_points_on_a.push_back(c.points[i] - c.depths[i] * out.normal);
      out.depth = std::max(out.depth, -c.depths[i]);
    }
  }
  {
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector gjk(&box_a, &box_b, &simplex, &epa);
    btPointCollector c;
    gjk.getClosestPoints(input, c, nullptr);
    out.gjk_ok = c.m_hasResult;
    if (c.m_hasResult) {
      out.gjk_distance = double(c.m_distance);
      out.gjk_normal = -from_bullet(c.m_normalOnBInWorld);
    }
  }
  return out;
}

// ---- Support functions ------------------------------------------------------------------------------

double directional_overlap(const Points& a, const Points& b, const Point& u) {
  double max_a = -INFINITY, min_b = INFINITY;
  for (const Point& x : a) max_a = std::max(max_a, x.dot(u));
  for (const Point& y : b) min_b = std::min(min_b, y.dot(u));
  return max_a - min_b;
}

// ---- Helpers ----------------------------------------------------------------------------------------

Points box_vertices(const Point& half, const Point& pos, const Eigen::MatrixXd& rot) {
  const int n = int(half.size());
  Points out;
  for (int mask = 0; mask < (1 << n); ++mask) {
    Point corner(n);
    for (int k = 0; k < n; ++k) corner[k] = (mask >> k) & 1 ? half[k] : -half[k];
    out.push_back(pos + rot * corner);
  }
  return out;
}

Eigen::MatrixXd random_rotation(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = g(rng);
  return dense::haar_rotation(m);
}

Points random_points_in_ball(int n, int count, double radius, const Point& centre, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Points out;
  for (int i = 0; i < count; ++i) {
    Point x(n);
    for (int k = 0; k < n; ++k) x[k] = g(rng);
    out.push_back(centre + x.normalized() * radius * std::pow(u(rng), 1.0 / n));
  }
  return out;
}

}  // namespace wedge::oracle
