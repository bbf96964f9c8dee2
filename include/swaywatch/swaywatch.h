/* swaywatch.h - everything public, in one include. */
#ifndef SWAYWATCH_H
#define SWAYWATCH_H

#include "swaywatch/alarm.h"
#include "swaywatch/csv.h"
#include "swaywatch/engine.h"
#include "swaywatch/model.h"
#include "swaywatch/pulse.h"
#include "swaywatch/scene.h"
#include "swaywatch/status.h"
#include "swaywatch/sweep.h"

#define SW_VERSION "0.1.0"
const char *sw_version(void);

#endif
