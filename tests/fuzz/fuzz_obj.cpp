// libFuzzer target for the obj reader (see reader_target.hpp).
#define EMBER_FUZZ_FORMAT ember::MeshFormat::Obj
#include "fuzz/reader_target.hpp"
