// The scenes of wedge_bench_contact (bench/README.md, "Contact"), built the same way in Wedge and in the
// peer engines: Box2D 2.4 for the 2D pyramid, Bullet 3.24 (single precision) for the 3D pile. The peer
// scenes copy every initial position and orientation from the Wedge world made by the wedge::scenes
// builders, so the two engines start from the same state.
//
// Matched settings (see make_settings and the peer constructors):
//   time step 1/60 s, gravity 9.81 m/s^2 along -x_1, box half extent 0.5 m, density 1000 kg/m^n,
//   friction 0.6 per pair, restitution 0; Box2D's velocity/position iterations 8/3 against Wedge's
//   contact/position iterations 8/3; Bullet's 10 solver iterations against Wedge's 10 contact iterations.
#pragma once

#include <box2d/box2d.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <vector>

#include "wedge_scenes.hpp"

namespace wedge::bench {

// ------------------------------------------------------------------ Box2D 2.4
// The same pyramid: a static edge along the ground line y = 0 and one b2PolygonShape box per Wedge box,
// at the Wedge box's centre and angle.
struct Box2DScene {
  std::unique_ptr<b2World> world;
  std::vector<b2Body*> boxes;  // in Wedge's body order (ground excluded)

  Box2DScene(const World<2>& layout, bool sleep) : world(std::make_unique<b2World>(b2Vec2(0.0f, float(-kGravity)))) {
    world->SetAllowSleeping(sleep);
    b2BodyDef ground_def;
    b2Body* ground = world->CreateBody(&ground_def);
    b2EdgeShape edge;
    edge.SetTwoSided(b2Vec2(-100.0f, 0.0f), b2Vec2(100.0f, 0.0f));
    b2FixtureDef ground_fixture;
    ground_fixture.shape = &edge;
    ground_fixture.friction = float(kFriction);
    ground->CreateFixture(&ground_fixture);

    b2PolygonShape box;
    box.SetAsBox(float(kHalf), float(kHalf));
    b2FixtureDef fixture;
    fixture.shape = &box;
    fixture.density = float(kDensity);
    fixture.friction = float(kFriction);
    for (const Body<2>& b : layout.bodies()) {
      if (!b.is_dynamic()) continue;
      const Mat<2> r = to_matrix(b.rotor);
      b2BodyDef def;
      def.type = b2_dynamicBody;
      def.position.Set(float(b.center[0]), float(b.center[1]));
      def.angle = float(std::atan2(r(1, 0), r(0, 0)));
      b2Body* body = world->CreateBody(&def);
      body->CreateFixture(&fixture);
      boxes.push_back(body);
    }
  }
  void step() { world->Step(float(kDt), 8, 3); }
  int awake_count() const {
    int n = 0;
    for (const b2Body* b : boxes) n += b->IsAwake() ? 1 : 0;
    return n;
  }
};

// ------------------------------------------------------------------ Bullet 3.24
// The same pile: a static plane y = 0 (btStaticPlaneShape) and one btBoxShape per Wedge box at the Wedge
// box's centre and rotation, in a btDiscreteDynamicsWorld with btDbvtBroadphase and the sequential
// impulse solver. Bullet multiplies the two friction coefficients of a pair, so each body gets
// sqrt(0.6) to give a pair 0.6, as Wedge's geometric mean does.
struct BulletScene {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  btStaticPlaneShape plane{btVector3(0, 1, 0), 0};
  btBoxShape box{btVector3(btScalar(kHalf), btScalar(kHalf), btScalar(kHalf))};
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // [0] is the ground, then Wedge's boxes in order

  BulletScene(const World<3>& layout, bool sleep) {
    world.setGravity(btVector3(0, btScalar(-kGravity), 0));
    world.getSolverInfo().m_numIterations = 10;
    const btScalar friction = btScalar(std::sqrt(kFriction));
    add(&plane, btTransform::getIdentity(), 0, friction);
    const btScalar mass = btScalar(kDensity * 8.0 * kHalf * kHalf * kHalf);
    for (const Body<3>& b : layout.bodies()) {
      if (!b.is_dynamic()) continue;
      const Mat<3> r = to_matrix(b.rotor);
      const btMatrix3x3 basis(btScalar(r(0, 0)), btScalar(r(0, 1)), btScalar(r(0, 2)), btScalar(r(1, 0)),
                              btScalar(r(1, 1)), btScalar(r(1, 2)), btScalar(r(2, 0)), btScalar(r(2, 1)),
                              btScalar(r(2, 2)));
      btRigidBody* body =
          add(&box, btTransform(basis, btVector3(btScalar(b.center[0]), btScalar(b.center[1]), btScalar(b.center[2]))),
              mass, friction);
      if (!sleep) body->setActivationState(DISABLE_DEACTIVATION);
    }
  }
  ~BulletScene() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
  BulletScene(const BulletScene&) = delete;
  BulletScene& operator=(const BulletScene&) = delete;

  // Exactly one substep of kDt (maxSubSteps = 0: the given time step is used as it is).
  void step() { world.stepSimulation(btScalar(kDt), 0); }
  int awake_count() const {
    int n = 0;
    for (std::size_t i = 1; i < bodies.size(); ++i) n += bodies[i]->isActive() ? 1 : 0;
    return n;
  }

 private:
  btRigidBody* add(btCollisionShape* shape, const btTransform& pose, btScalar mass, btScalar friction) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    motion_states.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(mass, motion_states.back().get(), shape, inertia);
    info.m_friction = friction;
    info.m_restitution = 0;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(bodies.back().get());
    return bodies.back().get();
  }
};

template <int N>
int awake_count(const World<N>& w) {
  int n = 0;
  for (int i = 0; i < w.body_count(); ++i) n += w.bodies()[i].is_dynamic() && w.is_awake(BodyId{std::uint32_t(i)}) ? 1 : 0;
  return n;
}

// Largest speed of a box's centre (m/s), as max_speed(World) in wedge_scenes.hpp.
inline double max_speed(const Box2DScene& s) {
  double v = 0.0;
  for (const b2Body* b : s.boxes) v = std::max(v, double(b->GetLinearVelocity().Length()));
  return v;
}
inline double max_speed(const BulletScene& s) {
  double v = 0.0;
  for (const auto& b : s.bodies) v = std::max(v, double(b->getLinearVelocity().length()));
  return v;
}

}  // namespace wedge::bench
