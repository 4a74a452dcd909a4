// The /checkpoint group of an incomplete result file (docs/restart.md).
#pragma once

#include <hdf5.h>

#include "latfrac/fracture/run_control.h"

namespace latfrac {

void write_checkpoint_group(hid_t file, const RunCheckpoint& checkpoint);
// Throws InputError naming the missing or misshapen object.
RunCheckpoint read_checkpoint_group(hid_t file);

}  // namespace latfrac
