// The stored preset banks (preset_banks.inc) are the designs bit for bit, so a preset transform
// built from the table equals the one built by designing: streams naming a preset keep their
// coefficients. After a change to the design or the presets, regenerate the table with
// `build/train/preset_bank_table > transforms/pups/preset_banks.inc`.
#include <gtest/gtest.h>

#include <vector>

#include "transforms/pups/design.h"
#include "transforms/pups/pups_transform.h"
#include "transforms/pups/stored_presets.h"
#include "transforms/spec.h"

namespace pupwave::pups {
namespace {

TEST(StoredPresets, EveryPresetIsStoredAsItsDesign) {
  for (const Preset& p : presets()) {
    const auto stored = stored_preset_bank(p.name);
    ASSERT_TRUE(stored.has_value()) << p.name << " missing: regenerate preset_banks.inc";
    const FilterBank designed = design_preset(p.name);
    // Byte equality of the serialized forms compares every double bit for bit (== would call
    // -0 and +0 equal); the struct comparison covers fields to_bytes might not carry.
    EXPECT_EQ(to_bytes(*stored), to_bytes(designed)) << p.name << ": regenerate preset_banks.inc";
    EXPECT_TRUE(*stored == designed) << p.name;
  }
}

TEST(StoredPresets, UnknownNamesAreNotStored) {
  EXPECT_FALSE(stored_preset_bank("no-such-preset").has_value());
  EXPECT_FALSE(stored_preset_bank("").has_value());
}

// The transform built from the spec (which takes the stored bank) analyzes exactly as one built
// from a fresh design.
TEST(StoredPresets, SpecTransformEqualsDesignedTransform) {
  for (const char* name : {"cinpact-interp-vm4", "chaikin", "poly16-vm4-cg"}) {
    const auto from_spec = make_transform(std::string("pups:") + name);
    const Preset* preset = nullptr;
    for (const Preset& p : presets())
      if (p.name == name) preset = &p;
    ASSERT_NE(preset, nullptr);
    const auto designed =
        make_pups_transform(design_preset(name), std::string("pups:") + name, preset->boundary);
    EXPECT_EQ(from_spec->spec(), designed->spec());
    std::vector<double> a(77), b(77);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = b[i] = double((i * 37) % 19) - 4.5;
    from_spec->analyze(std::span<double>(a));
    designed->analyze(std::span<double>(b));
    EXPECT_EQ(a, b) << name;
  }
}

}  // namespace
}  // namespace pupwave::pups
