// Bodies for tests that drive the contact pipeline (find_contacts, the soft step) directly, without a
// World: the body, shape and material arrays it reads, filled one body at a time.
#pragma once

#include <memory>
#include <vector>

#include "contact/contact_system.hpp"
#include "wedge/mass.hpp"

template <int N>
struct ContactBodies {
  std::vector<wedge::Body<N>> bodies;
  wedge::contact::Shapes<N> shapes;
  std::vector<wedge::Material> materials;

  // A body of the shape at `at` (dynamic ones of density 1000 kg/m^N); returns its index.
  int add(std::shared_ptr<const wedge::Shape<N>> shape, wedge::BodyType type, const wedge::Vec<N>& at) {
    wedge::BodyDef<N> def = type == wedge::BodyType::Static ? wedge::BodyDef<N>{} : wedge::body_def<N>(shape, 1000.0);
    def.shape = shape;
    def.type = type;
    def.position = at;
    bodies.push_back(wedge::make_body(def));
    shapes.push_back(shape);
    materials.push_back(def.material);
    return int(bodies.size()) - 1;
  }
  // The ground: the half-space x_1 <= 0, static.
  int add_ground() {
    return add(std::make_shared<const wedge::Shape<N>>(wedge::Shape<N>::halfspace(wedge::Vec<N>::Unit(1), 0.0)),
               wedge::BodyType::Static, wedge::Vec<N>::Zero());
  }
};
