// The component framework: parsing model strings, order, parameters, and adding a component
// from outside src/sim (what rir-diagnose does).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/model.h"
#include "sim/room_list.h"
#include "sim_test_util.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {

TEST(SimModel, GasIsImageSourcesPlusDiffuseTail) {
  const Model gas = Model::parse("gas");
  EXPECT_EQ(gas.component_names(), (std::vector<std::string>{"ism", "diffuse"}));
  // Evaluation order is fixed by stage and order, not by how the user wrote it.
  EXPECT_EQ(Model::parse("diffuse+ism").component_names(), gas.component_names());
  EXPECT_TRUE(gas.has_component("diffuse"));
}

TEST(SimModel, BadModelStringsAreErrors) {
  EXPECT_THROW(Model::parse("gas+nosuch"), Error);
  EXPECT_THROW(Model::parse("gas+ism"), Error);           // ism twice
  EXPECT_THROW(Model::parse("ism:bogus=1"), Error);       // unknown parameter
  EXPECT_THROW(Model::parse("ism:max_images=abc"), Error);
  EXPECT_THROW(Model::parse("ism:max_images=0"), Error);
  EXPECT_THROW(Model::parse("gas:max_images=5"), Error);  // alias takes no parameters
  EXPECT_THROW(Model::parse(""), Error);
  EXPECT_THROW(Model::parse("ism+"), Error);
  try {
    Model::parse("gas+nosuch");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nosuch"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("ism"), std::string::npos) << "lists the known components";
  }
}

TEST(SimModel, ComponentsSplitTheResponse) {
  // "ism" alone has no energy after its transition (~90 ms here); the full model carries the
  // decay on (at 0.3 s a T60 of 0.6 s leaves ~-30 dB of the energy).
  const std::string line = "c room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6";
  const Signal ism = test::simulate(line, "ism", 16000, 1.0);
  const Signal gas = test::simulate(line, "gas", 16000, 1.0);
  const size_t late = 4800;
  EXPECT_LT(test::energy(ism.samples, late), 1e-12 * test::energy(ism.samples));
  EXPECT_GT(test::energy(gas.samples, late), 1e-4 * test::energy(gas.samples));
  // The direct sound is identical in both.
  const size_t peak = test::peak_index(ism.samples);
  EXPECT_NEAR(gas.samples[peak], ism.samples[peak], 1e-3 * std::abs(ism.samples[peak]));
}

// A component defined outside src/sim: scales the broadband RIR. Registered at run time.
class GainComponent : public ModelComponent {
 public:
  explicit GainComponent(ComponentParams& p) : gain_(p.number("gain", 1.0)) {}
  std::string name() const override { return "test_gain"; }
  ModelStage stage() const override { return ModelStage::kBroadband; }
  int order() const override { return 500; }
  void process_rir(const RenderContext&, std::vector<float>& x) const override {
    for (float& v : x) v *= static_cast<float>(gain_);
  }

 private:
  double gain_;
};

// A room-stage component: doubles every absorption coefficient (capped at 1).
class DoubleAbsorption : public ModelComponent {
 public:
  explicit DoubleAbsorption(ComponentParams&) {}
  std::string name() const override { return "test_double_absorption"; }
  ModelStage stage() const override { return ModelStage::kRoom; }
  int order() const override { return 100; }
  void adjust_room(RoomSpec& room) const override {
    for (auto& s : room.absorption)
      for (double& a : s) a = std::min(1.0, 2.0 * a);
  }
};

TEST(SimModel, ExternalComponentsPlugIn) {
  register_model_component("test_gain", "scales the RIR", [](ComponentParams& p) {
    return std::make_unique<GainComponent>(p);
  });
  register_model_component("test_double_absorption", "doubles absorption", [](ComponentParams& p) {
    return std::make_unique<DoubleAbsorption>(p);
  });
  register_model_alias("test_gas2", "gas+test_gain:gain=2");
  EXPECT_NE(model_components_help().find("test_gain"), std::string::npos);

  const std::string line = "p room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 absorption=0.15";
  const Signal base = test::simulate(line, "gas");
  const Signal twice = test::simulate(line, "test_gain:gain=2+gas");
  const Signal alias = test::simulate(line, "test_gas2");
  ASSERT_EQ(base.samples.size(), twice.samples.size());
  for (size_t i = 0; i < base.samples.size(); i += 97) {
    ASSERT_FLOAT_EQ(twice.samples[i], 2.0f * base.samples[i]);
    ASSERT_FLOAT_EQ(alias.samples[i], twice.samples[i]);
  }
  // The room stage runs before rendering: doubling absorption 0.15 equals asking for 0.3.
  const Signal doubled = test::simulate(line, "gas+test_double_absorption");
  const Signal direct = test::simulate("p room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 absorption=0.3", "gas");
  EXPECT_EQ(doubled.samples, direct.samples);
  const Model m = Model::parse("gas+test_double_absorption");
  EXPECT_EQ(m.component_names().front(), "test_double_absorption");
}

TEST(SimModel, AutoLengthCoversTheDecay) {
  const RoomSpec room = parse_room_list_line("a room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.3,0.4,0.5,0.8,0.6,0.5,0.4,0.3", "x:1");
  const double length = Model::parse("gas").auto_length_s(room);
  EXPECT_GE(length, 0.8 + room.source_mic_distance_m() / 343.0);
  EXPECT_LT(length, 0.83);
  EXPECT_NEAR(Model::parse("ism").auto_length_s(room), 0.1, 0.1);  // images only: short
}

}  // namespace
}  // namespace tsrir::sim
