// Box2D v3 (erincatto/box2d, C API) as a peer of wedge_bench_peers, built from a local source checkout
// (-DWEDGE_BOX2D_V3_DIR=...; never vendored, never needed by CI). The scene copies every box's centre and
// angle from a Wedge 2D world (wedge_scenes.hpp) and uses Box2D v3's own defaults otherwise: 4 substeps,
// soft contacts, its solver's relax and restitution passes; one worker thread, or more through Box2D
// v3's own scheduler (b2WorldDef::workerCount, as its samples run it). The ground is a static box
// of half size 100 x 1 m under y = 0, as in Box2D's own large_pyramid benchmark.
#pragma once

#include <box2d/box2d.h>

#include <vector>

#include "wedge_scenes.hpp"

namespace wedge::bench {

class Box2DV3Scene {
 public:
  // contact_hertz: 0 keeps Box2D v3's default (30 Hz); it caps the spring at an eighth of the sub-step
  // rate, as Wedge does.
  Box2DV3Scene(const World<2>& layout, bool sleep, int workers = 1, int substeps = 4, float contact_hertz = 0.0f)
      : substeps_(substeps) {
    b2WorldDef def = b2DefaultWorldDef();
    def.workerCount = workers;
    if (contact_hertz > 0.0f) def.contactHertz = contact_hertz;
    def.gravity = b2Vec2{0.0f, float(-kGravity)};
    def.enableSleep = sleep;
    world_ = b2CreateWorld(&def);
    b2BodyDef ground_def = b2DefaultBodyDef();
    ground_def.position = b2Pos{0.0f, -1.0f};
    const b2BodyId ground = b2CreateBody(world_, &ground_def);
    const b2Polygon ground_box = b2MakeBox(100.0f, 1.0f);
    b2ShapeDef shape = b2DefaultShapeDef();
    shape.material.friction = float(kFriction);
    shape.material.restitution = 0.0f;
    b2CreatePolygonShape(ground, &shape, &ground_box);
    shape.density = float(kDensity);
    const b2Polygon box = b2MakeSquare(float(kHalf));
    for (const Body<2>& b : layout.bodies()) {
      if (!b.is_dynamic()) continue;
      const Mat<2> r = to_matrix(b.rotor);
      b2BodyDef body = b2DefaultBodyDef();
      body.type = b2_dynamicBody;
      body.position = b2Pos{float(b.center[0]), float(b.center[1])};
      body.rotation = b2MakeRot(float(std::atan2(r(1, 0), r(0, 0))));
      const b2BodyId id = b2CreateBody(world_, &body);
      b2CreatePolygonShape(id, &shape, &box);
      boxes_.push_back(id);
    }
  }
  ~Box2DV3Scene() { b2DestroyWorld(world_); }
  Box2DV3Scene(const Box2DV3Scene&) = delete;
  Box2DV3Scene& operator=(const Box2DV3Scene&) = delete;

  void step() { b2World_Step(world_, float(kDt), substeps_); }  // (4 substeps: Box2D v3's recommended default)
  double max_speed() const {
    double v = 0.0;
    for (const b2BodyId id : boxes_) v = std::max(v, double(b2Length(b2Body_GetLinearVelocity(id))));
    return v;
  }
  int moving(double speed) const {
    int n = 0;
    for (const b2BodyId id : boxes_) n += b2Length(b2Body_GetLinearVelocity(id)) > speed ? 1 : 0;
    return n;
  }
  double height(std::size_t k) const { return double(b2Body_GetPosition(boxes_[k]).y); }
  std::size_t count() const { return boxes_.size(); }
  b2WorldId world() const { return world_; }  // (for b2World_GetProfile: peers_profile.cpp)

 private:
  int substeps_;
  b2WorldId world_;
  std::vector<b2BodyId> boxes_;  // in Wedge's body order (ground excluded)
};

// Box2D v3's own joint_grid benchmark scene (shared/benchmarks.c, CreateJointGrid), built as it builds
// it: disks of radius 0.4 m that a filter keeps from colliding, revolute joints at Box2D's defaults
// (60 Hz, damping ratio 2), 4 sub-steps, sleeping off; one worker thread. The Wedge twin is
// wedge_scenes.hpp's joint_grid.
class Box2DV3JointGrid {
 public:
  explicit Box2DV3JointGrid(int n) {
    b2WorldDef def = b2DefaultWorldDef();
    def.workerCount = 1;
    def.gravity = b2Vec2{0.0f, float(-kGravity)};
    def.enableSleep = false;
    world_ = b2CreateWorld(&def);
    b2ShapeDef shape = b2DefaultShapeDef();
    shape.density = 1.0f;
    shape.filter.categoryBits = 2;
    shape.filter.maskBits = ~2u;
    const b2Circle circle = {{0.0f, 0.0f}, float(kGridRadius)};
    b2RevoluteJointDef joint = b2DefaultRevoluteJointDef();
    b2BodyDef body = b2DefaultBodyDef();
    std::vector<b2BodyId> ids;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < n; ++i) {
        body.type = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0 ? b2_staticBody : b2_dynamicBody;
        body.position = b2Pos{float(k), float(-i)};
        const b2BodyId id = b2CreateBody(world_, &body);
        b2CreateCircleShape(id, &shape, &circle);
        if (i > 0) {
          joint.base.bodyIdA = ids[ids.size() - 1];
          joint.base.bodyIdB = id;
          joint.base.localFrameA.p = b2Vec2{0.0f, -0.5f};
          joint.base.localFrameB.p = b2Vec2{0.0f, 0.5f};
          b2CreateRevoluteJoint(world_, &joint);
        }
        if (k > 0) {
          joint.base.bodyIdA = ids[ids.size() - std::size_t(n)];
          joint.base.bodyIdB = id;
          joint.base.localFrameA.p = b2Vec2{0.5f, 0.0f};
          joint.base.localFrameB.p = b2Vec2{-0.5f, 0.0f};
          b2CreateRevoluteJoint(world_, &joint);
        }
        ids.push_back(id);
        if (body.type == b2_dynamicBody) bodies_.push_back(id);
      }
  }
  ~Box2DV3JointGrid() { b2DestroyWorld(world_); }
  Box2DV3JointGrid(const Box2DV3JointGrid&) = delete;
  Box2DV3JointGrid& operator=(const Box2DV3JointGrid&) = delete;

  void step() { b2World_Step(world_, float(kDt), 4); }
  double max_speed() const {
    double v = 0.0;
    for (const b2BodyId id : bodies_) v = std::max(v, double(b2Length(b2Body_GetLinearVelocity(id))));
    return v;
  }
  int moving(double speed) const {
    int count = 0;
    for (const b2BodyId id : bodies_) count += b2Length(b2Body_GetLinearVelocity(id)) > speed ? 1 : 0;
    return count;
  }
  double height(std::size_t k) const { return double(b2Body_GetPosition(bodies_[k]).y); }
  std::size_t count() const { return bodies_.size(); }

 private:
  b2WorldId world_;
  std::vector<b2BodyId> bodies_;  // the dynamic ones, in creation order
};

}  // namespace wedge::bench
