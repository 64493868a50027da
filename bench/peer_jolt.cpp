// Jolt Physics as a peer of wedge_bench_peers (peer_jolt.hpp). This file alone includes Jolt: Jolt's
// target carries its compiler flags (AVX2, FMA, ...) to whatever compiles against it, and Eigen's
// alignment, hence the layout of Wedge's types, would then differ from wedge_core's. So the scene is
// handed over as plain numbers and this file is compiled in a library of its own.
#include "peer_jolt.hpp"

#include <Jolt/Jolt.h>
// (Jolt.h first: the other Jolt headers rely on it)
#include <Jolt/Core/Factory.h>
#include <Jolt/Core/JobSystemSingleThreaded.h>
#include <Jolt/Core/JobSystemThreadPool.h>
#include <Jolt/Core/TempAllocator.h>
#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/PhysicsSettings.h>
#include <Jolt/Physics/PhysicsSystem.h>
#include <Jolt/RegisterTypes.h>

#include <algorithm>

namespace wedge::bench {

namespace {

// Two object layers (static, moving) on two broad-phase layers, as in Jolt's HelloWorld.
constexpr JPH::ObjectLayer kStatic = 0, kMoving = 1;
class BroadPhaseLayers final : public JPH::BroadPhaseLayerInterface {
 public:
  JPH::uint GetNumBroadPhaseLayers() const override { return 2; }
  JPH::BroadPhaseLayer GetBroadPhaseLayer(JPH::ObjectLayer layer) const override {
    return JPH::BroadPhaseLayer(JPH::BroadPhaseLayer::Type(layer));
  }
#if defined(JPH_EXTERNAL_PROFILE) || defined(JPH_PROFILE_ENABLED)
  const char* GetBroadPhaseLayerName(JPH::BroadPhaseLayer layer) const override {
    return JPH::BroadPhaseLayer::Type(layer) == 0 ? "static" : "moving";
  }
#endif
};
class ObjectVsBroadPhase final : public JPH::ObjectVsBroadPhaseLayerFilter {
 public:
  bool ShouldCollide(JPH::ObjectLayer layer, JPH::BroadPhaseLayer bp) const override {
    return layer == kMoving || JPH::BroadPhaseLayer::Type(bp) == kMoving;
  }
};
class ObjectPairs final : public JPH::ObjectLayerPairFilter {
 public:
  bool ShouldCollide(JPH::ObjectLayer a, JPH::ObjectLayer b) const override { return a == kMoving || b == kMoving; }
};

// Jolt's process-wide set-up, once.
void init_once() {
  static const bool done = [] {
    JPH::RegisterDefaultAllocator();
    JPH::Factory::sInstance = new JPH::Factory();
    JPH::RegisterTypes();
    return true;
  }();
  (void)done;
}

}  // namespace

struct JoltScene::Impl {
  Impl(std::size_t bodies, int threads) : temp(64 * 1024 * 1024) {
    if (threads > 1)
      jobs = std::make_unique<JPH::JobSystemThreadPool>(JPH::cMaxPhysicsJobs, JPH::cMaxPhysicsBarriers, threads - 1);
    else
      jobs = std::make_unique<JPH::JobSystemSingleThreaded>(JPH::cMaxPhysicsJobs);
    system.Init(JPH::uint(bodies) + 16, 0, 65536, 65536, layers, object_vs_bp, pairs);
  }
  BroadPhaseLayers layers;
  ObjectVsBroadPhase object_vs_bp;
  ObjectPairs pairs;
  JPH::TempAllocatorImpl temp;
  std::unique_ptr<JPH::JobSystem> jobs;
  JPH::PhysicsSystem system;
  std::vector<JPH::BodyID> boxes;
  float dt = 0.0f;
  const JPH::BodyInterface& bi() const { return system.GetBodyInterfaceNoLock(); }
};

JoltScene::JoltScene(const std::vector<BoxPose>& boxes, const JoltSettings& s) {
  init_once();
  impl_ = std::make_unique<Impl>(boxes.size(), s.threads);
  impl_->dt = float(s.dt);
  impl_->system.SetGravity(JPH::Vec3(0.0f, float(-s.gravity), 0.0f));
  JPH::BodyInterface& bi = impl_->system.GetBodyInterface();
  JPH::BodyCreationSettings ground(new JPH::BoxShape(JPH::Vec3(500.0f, 1.0f, 500.0f)), JPH::RVec3(0.0f, -1.0f, 0.0f),
                                   JPH::Quat::sIdentity(), JPH::EMotionType::Static, kStatic);
  ground.mFriction = float(s.friction);
  bi.CreateAndAddBody(ground, JPH::EActivation::DontActivate);
  const JPH::RefConst<JPH::Shape> box = new JPH::BoxShape(JPH::Vec3::sReplicate(float(s.half)));
  for (const BoxPose& p : boxes) {
    JPH::BodyCreationSettings b(box, JPH::RVec3(float(p.position[0]), float(p.position[1]), float(p.position[2])),
                                JPH::Quat(float(p.rotation[1]), float(p.rotation[2]), float(p.rotation[3]),
                                          float(p.rotation[0]))
                                    .Normalized(),
                                JPH::EMotionType::Dynamic, kMoving);
    b.mFriction = float(s.friction);
    b.mRestitution = 0.0f;
    b.mAllowSleeping = s.sleep;
    b.mOverrideMassProperties = JPH::EOverrideMassProperties::CalculateInertia;
    b.mMassPropertiesOverride.mMass = float(s.density * 8.0 * s.half * s.half * s.half);
    impl_->boxes.push_back(bi.CreateAndAddBody(b, JPH::EActivation::Activate));
  }
  impl_->system.OptimizeBroadPhase();
}

JoltScene::~JoltScene() = default;

void JoltScene::step() { impl_->system.Update(impl_->dt, 1, &impl_->temp, impl_->jobs.get()); }

double JoltScene::max_speed() const {
  double v = 0.0;
  for (const JPH::BodyID id : impl_->boxes) v = std::max(v, double(impl_->bi().GetLinearVelocity(id).Length()));
  return v;
}

int JoltScene::moving(double speed) const {
  int n = 0;
  for (const JPH::BodyID id : impl_->boxes) n += impl_->bi().GetLinearVelocity(id).Length() > speed ? 1 : 0;
  return n;
}

double JoltScene::height(std::size_t k) const {
  return double(impl_->bi().GetCenterOfMassPosition(impl_->boxes[k]).GetY());
}

std::size_t JoltScene::count() const { return impl_->boxes.size(); }

}  // namespace wedge::bench
