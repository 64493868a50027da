// The replay runtime's test program: every test reaches the runtime through the real OpenXR loader, which
// finds it through XR_RUNTIME_JSON (the manifest the build wrote; a caller's own value is kept, so the
// same tests can run against an installed copy).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

int main(int argc, char* argv[]) {
  setenv("XR_RUNTIME_JSON", WEDGE_XR_REPLAY_MANIFEST, 0);
  return Catch::Session().run(argc, argv);
}
