/* SPDX-License-Identifier: GPL-3.0-or-later */
/* export.h - SW_API marks what libswaywatch.so exports.  The library is
 * compiled with hidden visibility: the functions its modules share (the
 * model's right-hand sides, the step and event layers) stay internal, and
 * only the calls declared in these headers form the ABI. */
#ifndef SWAYWATCH_EXPORT_H
#define SWAYWATCH_EXPORT_H

#if defined(__GNUC__)
#define SW_API __attribute__((visibility("default")))
#else
#define SW_API
#endif

#endif
