// Element factory: built-in types, validation messages, host-registered types.
#include <gtest/gtest.h>

#include "DDC_ContinuumElement.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_Error.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

const std::string kWhere = "Mesh/Bodies/Upper Ring/Element";

/// The InputError message of `f`, or a test failure if it does not throw one.
template <class Fn>
std::string inputErrorOf(Fn f) {
  try {
    f();
  } catch (const ddc::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

bool contains(const std::string& s, const std::string& n) { return s.find(n) != std::string::npos; }

TEST(ElementFactory, BuiltinsCreateQuads) {
  const auto f = ddc::ElementFactory::withBuiltins();
  EXPECT_EQ(f.names(), (std::vector<std::string>{"Hex20", "Hex27", "Hex8", "Quad4", "Quad9", "Tet10", "Tet4"}));
  for (const auto& [name, n] : {std::pair<std::string, int>{"Quad4", 4}, {"Quad9", 9}}) {
    Teuchos::ParameterList p;
    p.set("Type", name);
    auto el = f.create(p, kWhere);
    ASSERT_TRUE(el);
    EXPECT_EQ(el->numNodes(), n);
    EXPECT_EQ(f.entry(name).numNodes, n);
    // Defaults are filled in, including the Material sublist.
    ASSERT_TRUE(p.isSublist("Material"));
    EXPECT_EQ(p.sublist("Material").get<std::string>("Type"), "Neo-Hookean");
    EXPECT_EQ(p.sublist("Material").get<double>("Young's Modulus"), 1000.0);
    auto ce = std::dynamic_pointer_cast<ddc::ContinuumElement>(el);
    ASSERT_TRUE(ce);
    EXPECT_EQ(ce->material().typeName(), "Neo-Hookean");
  }
  // Material choice and values reach the element.
  Teuchos::ParameterList p;
  p.set("Type", std::string("Quad9"));
  p.sublist("Material").set("Type", std::string("St. Venant-Kirchhoff"));
  p.sublist("Material").set("Young's Modulus", 210.0);
  auto ce = std::dynamic_pointer_cast<ddc::ContinuumElement>(f.create(p, kWhere));
  ASSERT_TRUE(ce);
  EXPECT_EQ(ce->material().typeName(), "St. Venant-Kirchhoff");
  EXPECT_EQ(ce->material().youngsModulus(), 210.0);
}

TEST(ElementFactory, BuiltinsCreate3dElements) {
  const auto f = ddc::ElementFactory::withBuiltins();
  for (const auto& [name, n] : {std::pair<std::string, int>{"Hex8", 8}, {"Hex20", 20}, {"Hex27", 27}, {"Tet4", 4},
                                {"Tet10", 10}}) {
    EXPECT_EQ(f.entry(name).numNodes, n) << name;
    EXPECT_EQ(f.entry(name).dim, 3) << name;
    Teuchos::ParameterList p;
    p.set("Type", name);
    p.sublist("Material").set("Type", std::string("St. Venant-Kirchhoff"));
    auto el = f.create(p, kWhere);
    ASSERT_TRUE(el);
    EXPECT_EQ(el->numNodes(), n);
    EXPECT_EQ(el->dim(), 3);
    EXPECT_EQ(p.sublist("Material").get<double>("Young's Modulus"), 1000.0) << "defaults filled in";
    auto ce = std::dynamic_pointer_cast<ddc::ContinuumElement>(el);
    ASSERT_TRUE(ce);
    EXPECT_EQ(ce->material().typeName(), "St. Venant-Kirchhoff");
  }
  // Quad4 and Tet4 have 4 nodes each: the dimension tells them apart.
  EXPECT_EQ(f.entry("Quad4").dim, 2);
  EXPECT_EQ(f.entry("Quad9").dim, 2);
}

TEST(ElementFactory, UnknownTypeListsKnownTypes) {
  const auto f = ddc::ElementFactory::withBuiltins();
  Teuchos::ParameterList p;
  p.set("Type", std::string("Quad8"));
  const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
  EXPECT_TRUE(contains(msg, "Quad8")) << msg;
  EXPECT_TRUE(contains(msg, "Quad4")) << msg;
  EXPECT_TRUE(contains(msg, "Quad9")) << msg;
  EXPECT_TRUE(contains(msg, kWhere + "/Type")) << msg;
  EXPECT_TRUE(contains(inputErrorOf([&] { f.entry("Tri3"); }), "Quad4"));
}

TEST(ElementFactory, MissingOrMistypedType) {
  const auto f = ddc::ElementFactory::withBuiltins();
  Teuchos::ParameterList p;
  std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
  EXPECT_TRUE(contains(msg, kWhere + "/Type")) << msg;
  EXPECT_TRUE(contains(msg, "Quad4")) << msg;
  p.set("Type", 4);
  msg = inputErrorOf([&] { f.create(p, kWhere); });
  EXPECT_TRUE(contains(msg, kWhere + "/Type")) << msg;
}

TEST(ElementFactory, MisspeltParametersNameThePath) {
  const auto f = ddc::ElementFactory::withBuiltins();
  {
    Teuchos::ParameterList p;
    p.set("Type", std::string("Quad4"));
    p.sublist("Material").set("Youngs Modulus", 5.0);
    const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
    EXPECT_TRUE(contains(msg, kWhere + "/Material/Youngs Modulus")) << msg;
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", std::string("Quad4"));
    p.set("Thickness", 2.0);
    const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
    EXPECT_TRUE(contains(msg, kWhere + "/Thickness")) << msg;
    EXPECT_TRUE(contains(msg, "Material")) << msg;  // lists the valid names
  }
  {
    // "Material" given as a parameter instead of a sublist.
    Teuchos::ParameterList p;
    p.set("Type", std::string("Quad4"));
    p.set("Material", std::string("Neo-Hookean"));
    const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
    EXPECT_TRUE(contains(msg, kWhere + "/Material")) << msg;
  }
}

TEST(ElementFactory, BadMaterialValues) {
  const auto f = ddc::ElementFactory::withBuiltins();
  {
    Teuchos::ParameterList p;
    p.set("Type", std::string("Quad9"));
    p.sublist("Material").set("Type", std::string("Neo Hookean"));
    const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
    EXPECT_TRUE(contains(msg, kWhere + "/Material/Type")) << msg;
    EXPECT_TRUE(contains(msg, "Neo-Hookean")) << msg;
    EXPECT_TRUE(contains(msg, "St. Venant-Kirchhoff")) << msg;
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", std::string("Quad9"));
    p.sublist("Material").set("Poisson's Ratio", 0.5);
    const std::string msg = inputErrorOf([&] { f.create(p, kWhere); });
    EXPECT_TRUE(contains(msg, kWhere + "/Material/Poisson's Ratio")) << msg;
  }
}

/// A host-defined 2-node axial spring, W = k/2 |u1 - u0|^2: shows that the
/// factory is open to types it was not compiled with.
class Spring : public ddc::Element {
 public:
  explicit Spring(double k) : k_(k) {}
  int numNodes() const override { return 2; }
  int dim() const override { return 2; }
  void compute(const ddc::NodalArray&, const ddc::NodalArray& u, unsigned, ddc::ElementResult& out) const override {
    const Eigen::Vector2d d = (u.row(1) - u.row(0)).transpose();
    out.energy = 0.5 * k_ * d.squaredNorm();
    out.residual.resize(4);
    out.residual << -k_ * d, k_ * d;
    out.tangent.setZero(4, 4);
  }
  void postprocess(const ddc::NodalArray&, const ddc::NodalArray&, ddc::ElementPostResult&) const override {}
  double minReferenceJacobian(const ddc::NodalArray&) const override { return 1.0; }

 private:
  double k_;
};

TEST(ElementFactory, HostRegisteredType) {
  auto f = ddc::ElementFactory::withBuiltins();
  auto valid = Teuchos::rcp(new Teuchos::ParameterList("Element"));
  valid->set("Stiffness", 1.0, "Spring stiffness k");
  f.add("Spring", {[](const Teuchos::ParameterList& p) {
                     return std::make_shared<Spring>(p.get<double>("Stiffness"));
                   },
                   valid, "Axial spring (test)", 2});
  EXPECT_TRUE(f.has("Spring"));
  EXPECT_FALSE(ddc::ElementFactory::withBuiltins().has("Spring")) << "registration must not leak";

  Teuchos::ParameterList p;
  p.set("Type", std::string("Spring"));
  p.set("Stiffness", 5.0);
  auto el = f.create(p, kWhere);
  ASSERT_TRUE(el);
  EXPECT_EQ(el->numNodes(), 2);
  Eigen::MatrixX2d X = Eigen::MatrixX2d::Zero(2, 2), u(2, 2);
  u << 0, 0, 0.2, 0;
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  EXPECT_NEAR(r.energy, 0.5 * 5.0 * 0.04, ddc::test::kRoundoff);

  // Its parameters are validated like the built-ins', and the error for an
  // unknown type now lists it.
  Teuchos::ParameterList bad;
  bad.set("Type", std::string("Spring"));
  bad.set("Stifness", 5.0);
  EXPECT_TRUE(contains(inputErrorOf([&] { f.create(bad, kWhere); }), kWhere + "/Stifness"));
  Teuchos::ParameterList unknown;
  unknown.set("Type", std::string("Beam"));
  EXPECT_TRUE(contains(inputErrorOf([&] { f.create(unknown, kWhere); }), "Spring"));
  // Defaults filled for the host type too.
  Teuchos::ParameterList dflt;
  dflt.set("Type", std::string("Spring"));
  f.create(dflt, kWhere);
  EXPECT_EQ(dflt.get<double>("Stiffness"), 1.0);
}

TEST(ElementFactory, RegisteredDimensionMustMatchTheElement) {
  // A registration mistake of a host code (a 2-D spring declared 3-D) is a
  // logic error, not an input error.
  auto f = ddc::ElementFactory::withBuiltins();
  ddc::ElementFactory::Entry e{[](const Teuchos::ParameterList&) { return std::make_shared<Spring>(1.0); },
                               Teuchos::null, "Axial spring (test)", 2};
  e.dim = 3;
  f.add("Spring", e);
  Teuchos::ParameterList p;
  p.set("Type", std::string("Spring"));
  EXPECT_THROW(f.create(p, kWhere), std::logic_error);
}

TEST(ElementFactory, ACreatorReadingAnUndeclaredParameterNamesIt) {
  // A host's creator that reads a parameter its entry does not declare (or
  // under another type) gets a message naming the type, the path and the
  // parameter, not Teuchos' exception.
  auto f = ddc::ElementFactory::withBuiltins();
  auto valid = Teuchos::rcp(new Teuchos::ParameterList("Element"));
  valid->set("Stiffness", 1.0, "Spring stiffness k");
  f.add("Spring", {[](const Teuchos::ParameterList& p) {
                     return std::make_shared<Spring>(p.get<double>("Stiffness") * p.get<double>("Scale"));
                   },
                   valid, "Axial spring (test)", 2});
  f.add("Typed Spring", {[](const Teuchos::ParameterList& p) {
                           return std::make_shared<Spring>(double(p.get<int>("Stiffness")));
                         },
                         valid, "Axial spring (test)", 2});
  for (const char* type : {"Spring", "Typed Spring"}) {
    Teuchos::ParameterList p;
    p.set("Type", std::string(type));
    try {
      f.create(p, kWhere);
      ADD_FAILURE() << type << ": no error";
    } catch (const std::logic_error& e) {
      const std::string msg = e.what();
      EXPECT_TRUE(contains(msg, std::string("element type '") + type + "' (" + kWhere + ")")) << msg;
      EXPECT_TRUE(contains(msg, std::string("the parameter '") + (type[0] == 'S' ? "Scale" : "Stiffness") + "'"))
          << msg;
      EXPECT_TRUE(contains(msg, "validParameters")) << msg;
    }
  }
}

TEST(ElementFactory, ValidParametersForDocumentation) {
  const auto f = ddc::ElementFactory::withBuiltins();
  auto v = f.validParametersFor("Quad9");
  ASSERT_TRUE(v->isParameter("Type"));
  EXPECT_TRUE(contains(v->getEntry("Type").docString(), "Quad4"));
  ASSERT_TRUE(v->isSublist("Material"));
  EXPECT_TRUE(v->sublist("Material").isParameter("Young's Modulus"));
  EXPECT_THROW(f.validParametersFor("Quad5"), ddc::InputError);
}

}  // namespace
