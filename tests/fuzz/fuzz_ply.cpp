// libFuzzer target for the ply reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Ply
#include "fuzz/reader_target.hpp"
