// libFuzzer target for the gltf reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Gltf
#include "fuzz/reader_target.hpp"
