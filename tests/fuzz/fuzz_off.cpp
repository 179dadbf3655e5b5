// libFuzzer target for the off reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Off
#include "fuzz/reader_target.hpp"
