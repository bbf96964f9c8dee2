/* SPDX-License-Identifier: GPL-3.0-or-later */
/* eventlog.h - lcm-logger event logs read in-process (libswaywatch_lcm),
 * never through the network: the events of one channel are yielded one
 * by one (sw_lcmlog_next(), as LCM's lcm_eventlog_read_next_event()), the
 * others counted and skipped; the monitor core takes them
 * (sw_mon_feed_log(), monitor.h).  No options are parsed and nothing is
 * printed here: what was read is told by the counts and, region by
 * region, by a callback.
 *
 * Event logs have no checksum, and their length fields are trusted by
 * LCM's own reader.  This reader trusts nothing: an event is taken only if
 * its header starts with the sync word, its channel length is 1 to
 * SW_LCMLOG_MAX_CHANNEL, its data length at most SW_LCMLOG_MAX_DATA and
 * no more than the bytes left in the file, its channel name holds no NUL
 * byte, and it is followed by the next sync word or by the end of the
 * file.  Anything else starts a corrupted region, which ends at the next
 * event that passes (found by scanning for the sync word from the byte
 * after the bad one's) or at the end of the file; each region is counted
 * once, so one damaged event cannot hide the rest of the log.  Lengths are
 * checked before anything is read or allocated by them: memory is fixed
 * (two small buffers) whatever the log says.
 *
 * Work is linear in the size of the log: the scan never goes back over a
 * byte it has passed, and checking a candidate event costs a bounded
 * number of bytes however long it claims to be.  counts.examined says how
 * many bytes were read.
 *
 * The sync word and sw_lcmlog_sniff() need nothing from LCM: a build
 * without LCM includes this header alone, to recognise lcm-logger files
 * and refuse them with the reason. */
#ifndef SWAYWATCH_LCM_EVENTLOG_H
#define SWAYWATCH_LCM_EVENTLOG_H

#include <signal.h>
#include <stddef.h>
#include <stdio.h>

/* The first four bytes of every event of an lcm-logger log (big-endian). */
#define SW_LCMLOG_SYNC 0xEDA1DA01u

/* Do the first len bytes of buf start like an lcm-logger event log? */
static inline int sw_lcmlog_sniff(const void *buf, size_t len)
{
    const unsigned char *b = buf;
    return len >= 4 && ((unsigned long)b[0] << 24 | (unsigned long)b[1] << 16 |
                        (unsigned long)b[2] << 8 | b[3]) == SW_LCMLOG_SYNC;
}

#define SW_LCMLOG_HEADER 28             /* sync, eventnum, timestamp, two lengths */
#define SW_LCMLOG_MAX_CHANNEL 63        /* LCM's longest channel name */
#define SW_LCMLOG_MAX_DATA (256L << 20) /* LCM's largest message, bytes */
#define SW_LCMLOG_CHANNEL "ACCEL"       /* the accel channel unless told otherwise */
/* Bytes of an accel-channel event's data handed on: more than
 * any accel_t (48 bytes), so a longer message is refused as what it is
 * (not an accel_t, or an accel_t with trailing bytes) without being read
 * whole. */
#define SW_LCMLOG_MAX_FEED 4096
/* A log that cannot seek (a pipe) is first copied to an unlinked temporary
 * file, at most this many bytes (4 GiB) unless the options say otherwise. */
#define SW_LCMLOG_SPOOL_MAX (4LL << 30)

/* A corrupted region, as it is skipped. */
typedef struct {
    long long offset; /* of its first byte in the log */
    long long length; /* bytes skipped */
    long events;      /* good events before it */
    char why[128];    /* what was wrong with its first byte's event */
} sw_lcmlog_region_t;

typedef struct {
    const char *channel; /* accel channel: an anchored regex, as LCM's subscriptions;
                            NULL = SW_LCMLOG_CHANNEL */
    int strict;          /* stop at the first corrupted region */
    /* if not NULL: reading stops before the next event once *stop is
     * non-zero (a signal handler sets it); counts.stopped says so */
    const volatile sig_atomic_t *stop;
    /* if not NULL: called once per corrupted region, when it ends */
    void (*on_region)(void *user, const sw_lcmlog_region_t *r);
    void *user;
    long long spool_max; /* bytes, see SW_LCMLOG_SPOOL_MAX; 0 = that */
} sw_lcmlog_opts_t;

typedef struct {
    long events;             /* events read */
    long on_channel;         /* events on the accel channel, yielded */
    long other_channels;     /* events on other channels, skipped */
    long corrupt;            /* corrupted regions skipped */
    long long corrupt_bytes; /* bytes in them */
    long long first_corrupt; /* offset of the first, -1 if none */
    long long size;          /* bytes in the log */
    long long examined;      /* bytes read from it (the work done) */
    long long first_utime;   /* us since 1970 on lcm-logger's clock: when it received the
                                first event on the accel channel (0: none) */
    long long last_utime;    /* the same of the last one */
    int spooled;             /* the log could not seek and was copied first */
    int stopped;             /* *opts.stop ended the read before the end of the log */
} sw_lcmlog_counts_t;

typedef struct sw_lcmlog sw_lcmlog_t;

/* Open the log at path (o may be NULL: defaults).  NULL on failure, with
 * *err: SW_EINVAL if o->channel is not a valid regular expression (checked
 * before the file is touched), SW_ENOTFOUND if the file cannot be opened
 * or copied (errno says why), SW_ETOOBIG if a log that cannot seek is
 * longer than the spool limit, SW_ENOMEM.  A file that cannot seek (a
 * FIFO, /dev/stdin on a pipe) is read whole first, as by
 * sw_lcmlog_open_stream(). */
sw_lcmlog_t *sw_lcmlog_open(const char *path, const sw_lcmlog_opts_t *o, int *err);

/* The same for a log already open as in, whose first len bytes (head) were
 * read from it already (to tell what it holds); in stays the caller's.  A
 * regular file is read through its own descriptor, from its start: head
 * is not needed.  Anything else (a pipe, standard input) is copied, head
 * first, to an unlinked temporary file in $TMPDIR (else /tmp), so the log
 * is read whole, once, and scanned like a file. */
sw_lcmlog_t *sw_lcmlog_open_stream(FILE *in, const void *head, size_t len,
                                   const sw_lcmlog_opts_t *o, int *err);
void sw_lcmlog_close(sw_lcmlog_t *log); /* NULL ok */

/* One event of the accel channel, as sw_lcmlog_next() yields it. */
typedef struct {
    long long offset;    /* of the event in the log */
    long long timestamp; /* us since 1970 on lcm-logger's clock: when it received it */
    double rx;           /* s, timestamp after the first accel event's, exact: the arrival
                            time a monitor is fed (NAN beyond 2^63 us) */
    const char *channel; /* its channel, NUL-terminated */
    const void *data;    /* the first len bytes of its data */
    size_t len;          /* at most SW_LCMLOG_MAX_FEED: a longer message is no accel_t, and
                            is refused as what it is without being read whole */
} sw_lcmlog_event_t;

/* The next event on the accel channel, in the order of the log: 1 with
 * *ev filled (its channel and data valid until the next call), 0 at the
 * end of the log or once *opts.stop is set (counts.stopped), or < 0:
 * SW_EPARSE with strict at the end of a corrupted region (reported
 * first; the next call goes on after it), SW_ENOTFOUND if the file cannot
 * be read (errno says why).  Events on other channels are counted and
 * skipped, corrupted regions reported and skipped. */
int sw_lcmlog_next(sw_lcmlog_t *log, sw_lcmlog_event_t *ev);

void sw_lcmlog_counts(const sw_lcmlog_t *log, sw_lcmlog_counts_t *c);

#endif
