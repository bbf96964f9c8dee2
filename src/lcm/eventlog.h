/* eventlog.h - lcm-logger event logs read in-process (libswaywatch_lcm):
 * the accel_t messages of one channel go to the monitor core (monitor.h)
 * by their own utime, never through the network.  No options are parsed
 * and nothing is printed here: what was read is told by the counts.
 *
 * Event logs have no checksum.  A corrupted region (a bad header, a length
 * pointing past the end of the file, junk between events) is skipped up to
 * the next sync word and counted once, so one damaged event cannot hide the
 * rest of the log.
 *
 * The sync word and sw_lcmlog_sniff() need nothing from LCM: a build
 * without LCM includes this header alone, to recognise lcm-logger files
 * and refuse them with the reason. */
#ifndef SWAYWATCH_LCM_EVENTLOG_H
#define SWAYWATCH_LCM_EVENTLOG_H

#include <stddef.h>

/* The first four bytes of every event of an lcm-logger log (big-endian). */
#define SW_LCMLOG_SYNC 0xEDA1DA01u

/* Do the first len bytes of buf start like an lcm-logger event log? */
static inline int sw_lcmlog_sniff(const void *buf, size_t len)
{
    const unsigned char *b = buf;
    return len >= 4 && ((unsigned long)b[0] << 24 | (unsigned long)b[1] << 16 |
                        (unsigned long)b[2] << 8 | b[3]) == SW_LCMLOG_SYNC;
}

struct sw_mon; /* sw_mon_t of monitor.h */

typedef struct {
    const char *channel; /* accel channel: an anchored regex, as LCM's subscriptions;
                            NULL = SW_MON_ACCEL_CHANNEL */
    int strict;          /* stop at the first corrupted region or refused sample */
} sw_lcmlog_opts_t;

typedef struct {
    long events;         /* events read */
    long on_channel;     /* events on the accel channel, fed to the monitor */
    long other_channels; /* events on other channels, skipped */
    long corrupt;        /* corrupted regions skipped */
} sw_lcmlog_counts_t;

typedef struct sw_lcmlog sw_lcmlog_t;

/* Open the log at path (o may be NULL: defaults).  NULL on failure, with
 * *err: SW_EINVAL if o->channel is not a valid regular expression (checked
 * before the file is touched), SW_ENOTFOUND if the file cannot be opened
 * (errno says why), SW_ENOMEM. */
sw_lcmlog_t *sw_lcmlog_open(const char *path, const sw_lcmlog_opts_t *o, int *err);
void sw_lcmlog_close(sw_lcmlog_t *log); /* NULL ok */

/* Read every event to the end of the log and feed those on the accel
 * channel to mon.  The logger's receive time of an event is the wall clock
 * of sw_mon_feed() (what max_skew compares a sample's utime with: a
 * sample stamped far from when it arrived would otherwise be accepted and
 * make every later one late) and its arrival time.  Returns SW_OK at the
 * end of the log; with strict, SW_EPARSE at the first corrupted region or
 * SW_EINVAL at the first sample mon refused (held ones included).  The
 * caller calls sw_mon_flush() after. */
int sw_lcmlog_read(sw_lcmlog_t *log, struct sw_mon *mon);

void sw_lcmlog_counts(const sw_lcmlog_t *log, sw_lcmlog_counts_t *c);

#endif
