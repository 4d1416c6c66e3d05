#pragma once
// A k = 1 shear wave v_y = 0.1 sin 2 pi x in a cooling gas at r = 0.9 (K = 0.08, phi = 0.02):
// 4 event-driven members of about 280 disks to t = 444, a few seconds; it measures the shear
// viscosity (docs/physics.md §14). The transport tests' small scene.
namespace granvv::testing {

constexpr const char* kSmallShearWave = R"toml(
[case]
name = "small_shear_wave"
[physics]
K = 0.08
q = 0.05
[initial]
type = "expression"
transverse_velocity = "0.1*sin(2*pi*x)"
[hydro]
transverse_velocity = true
cells = 100
[md]
enabled = true
engine = "event_driven"
area_fraction = 0.02
box_width = 20.0
seed = 3
ensemble = 4
t_end = 444.0
sample_interval = 47.0
output_times = [0.0, 111.0, 222.0, 333.0, 444.0]
bins = 16
checkpoint_interval = 0.0
[compare]
enabled = true
closures = ["dilute", "enskog"]
transport = "shear_viscosity"
transport_field = "v_y"
transport_phase = "sin"
)toml";

}  // namespace granvv::testing
