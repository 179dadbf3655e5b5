// libFuzzer target for the 3mf reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::ThreeMf
#include "fuzz/reader_target.hpp"
