/* SPDX-License-Identifier: GPL-3.0-or-later */
/* swaywatch.h - everything public, in one include. */
#ifndef SWAYWATCH_H
#define SWAYWATCH_H

#include "swaywatch/alarm.h"
#include "swaywatch/boundary.h"
#include "swaywatch/cost.h"
#include "swaywatch/csv.h"
#include "swaywatch/engine.h"
#include "swaywatch/export.h"
#include "swaywatch/forensics.h"
#include "swaywatch/gate.h"
#include "swaywatch/model.h"
#include "swaywatch/pool.h"
#include "swaywatch/pulse.h"
#include "swaywatch/reserve.h"
#include "swaywatch/risk.h"
#include "swaywatch/run.h"
#include "swaywatch/safety.h"
#include "swaywatch/scene.h"
#include "swaywatch/scheme.h"
#include "swaywatch/search.h"
#include "swaywatch/series.h"
#include "swaywatch/status.h"
#include "swaywatch/stream.h"
#include "swaywatch/units.h"
#include "swaywatch/whatif.h"

#include "swaywatch/version.h"

/* The library's version (SW_VERSION is the headers'). */
SW_API const char *sw_version(void);

#endif
