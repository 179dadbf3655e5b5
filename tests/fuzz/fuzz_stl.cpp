// libFuzzer target for the stl reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Stl
#include "fuzz/reader_target.hpp"
