// libFuzzer target for the glb reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Glb
#include "fuzz/reader_target.hpp"
