/* SPDX-License-Identifier: GPL-3.0-or-later */
/* auth.h - authenticated accel_t samples, after AUTOSAR SecOC: a
 * freshness value and a truncated MAC in every message (docs/security.md,
 * lcmtypes/accel_t.lcm), so that a monitor holding the key tells the
 * sensor's samples from anything else on the bus.
 *
 *   MAC = first 16 bytes of HMAC-SHA-256(key, C || 0x00 || M)
 *
 * C the channel name, M the 57 bytes of the encoded accel_t before its mac
 * field (fingerprint, utime, seq, ax, ay, az, freshness, key_id).  HMAC
 * from libsodium.  The channel is in it so that a sample of one sensor
 * cannot be replayed as another's on a second channel; the fingerprint, so
 * that the bytes are read under the layout they were signed in.
 *
 * Keys come from a key file, one key a line, as chrony's and NTP's keys:
 *
 *   # comment
 *   ID HMAC-SHA256 HEX:64 hexadecimal digits (32 bytes)
 *
 * ID 1 to 255 is the message's key_id; a sender signs with the last key of
 * its file, a monitor accepts every key of its own (two during a
 * change-over).  The library parses the text the caller read; reading the
 * file and checking its permissions are the command's.
 *
 * Both layouts of the accel channel are read here: accel_t and the older
 * accel_v1_t (no authentication fields) that senders without a key send.
 * No I/O, nothing printed; a keyring and a verifier allocate only when
 * made.  Internal to libswaywatch_lcm. */
#ifndef SWAYWATCH_LCM_AUTH_H
#define SWAYWATCH_LCM_AUTH_H

#include <stddef.h>
#include <stdint.h>

#include "swaywatch_accel_t.h"

#define SW_AUTH_KEY_LEN 32      /* bytes of a key (HMAC-SHA-256's block is 64, its output 32) */
#define SW_AUTH_MAC_LEN 16      /* bytes of the truncated MAC, accel_t.mac */
#define SW_AUTH_HEAD_LEN 57     /* bytes of an encoded accel_t the MAC covers (all before mac) */
#define SW_AUTH_ACCEL_LEN 73    /* bytes of an encoded accel_t */
#define SW_AUTH_ACCEL_V1_LEN 48 /* bytes of an encoded accel_v1_t */
#define SW_AUTH_ID_MAX 255      /* key ids are 1 .. 255; 0 in a message: none */
#define SW_AUTH_TYPE "HMAC-SHA256"
#define SW_AUTH_FILE_MAX 65536 /* bytes: a key file longer than this is no key file */

/* What a keyed monitor found in a message. */
typedef enum {
    SW_AUTH_OK = 0,      /* a MAC under a known key, and a fresh freshness */
    SW_AUTH_NONE,        /* no MAC: the accel_v1_t layout, or key_id 0 */
    SW_AUTH_UNKNOWN_KEY, /* a key id that is not in the key file */
    SW_AUTH_BAD_MAC,     /* the MAC does not match: another key, altered bytes, another
                            channel */
    SW_AUTH_REPLAYED,    /* authentic, but its freshness is not above the last accepted
                            under its key: a copy of an earlier message */
    SW_AUTH_NRESULTS
} sw_auth_result;

/* "ok", "unauthenticated", "unknown_key", "bad_mac", "replayed". */
const char *sw_auth_result_name(sw_auth_result r);
/* A phrase for people: "no MAC", "MAC under a key id not in the key file", ... */
const char *sw_auth_result_text(sw_auth_result r);

/* ---- keys ----------------------------------------------------------------------- */

typedef struct sw_keyring sw_keyring_t;

/* The keys of a key file's text (len bytes, not necessarily NUL-terminated;
 * name, for messages).  NULL with the reason in msg ("NAME:LINE: ...")
 * when a line is not a key line, an id is out of range or given twice, a
 * key is not 32 bytes of hexadecimal, the type is not HMAC-SHA256, or the
 * file holds no key. */
sw_keyring_t *sw_keyring_parse(const char *text, size_t len, const char *name, char *msg,
                               size_t msglen);
/* Wipes the keys (sodium_memzero) and frees; NULL ok. */
void sw_keyring_destroy(sw_keyring_t *k);

int sw_keyring_size(const sw_keyring_t *k);        /* keys in the file */
int sw_keyring_id(const sw_keyring_t *k, int i);   /* the i-th key's id, in file order */
int sw_keyring_has(const sw_keyring_t *k, int id); /* id is one of the keys */
int sw_keyring_signer(const sw_keyring_t *k);      /* the last key's id: a sender's */

/* The truncated MAC of the SW_AUTH_HEAD_LEN bytes head of an encoded
 * accel_t on channel, under key id: SW_OK, or SW_ENOTFOUND (no such
 * key). */
int sw_auth_mac(const sw_keyring_t *k, int id, const char *channel, const uint8_t *head,
                uint8_t mac[SW_AUTH_MAC_LEN]);

/* Sign msg for channel with key id: key_id and mac set (msg->freshness is
 * the caller's, one more than its last).  SW_OK, SW_ENOTFOUND (no such
 * key) or SW_EINVAL (msg cannot be encoded). */
int sw_auth_sign(const sw_keyring_t *k, int id, const char *channel, swaywatch_accel_t *msg);

/* ---- messages ------------------------------------------------------------------- */

/* One message of the accel channel in either layout, into s (for
 * accel_v1_t, freshness, key_id and mac are zero and *layout is 1; for
 * accel_t *layout is 2).  Returns the bytes it used (the caller compares
 * them with len: the decoders accept trailing bytes), or -1 if it is
 * neither (a wrong fingerprint, truncated). */
int sw_accel_decode(const void *data, size_t len, swaywatch_accel_t *s, int *layout);

/* ---- the verifier --------------------------------------------------------------- */

/* Where and why messages were refused, for the caller's report. */
typedef struct {
    long where;         /* the caller's count of the message (its place in the stream) */
    int key_id;         /* the message's, 0 = none */
    sw_auth_result why; /* SW_AUTH_OK: none refused yet */
    char channel[64];   /* the channel it came on */
} sw_auth_place_t;

typedef struct {
    long checked;                   /* messages checked */
    long refused[SW_AUTH_NRESULTS]; /* by result; refused[SW_AUTH_OK] is accepted */
    sw_auth_place_t first, last;    /* the first and the last message refused */
} sw_auth_facts_t;

typedef struct sw_auth sw_auth_t;

/* A verifier of keys (borrowed: it must outlive the verifier, or be
 * replaced by sw_auth_set_keys first), with the freshness seen under each
 * key id.  NULL when out of memory or libsodium cannot start. */
sw_auth_t *sw_auth_create(const sw_keyring_t *keys);
void sw_auth_destroy(sw_auth_t *a); /* NULL ok */

/* New keys (a key file read again): the freshness seen under each key id
 * is kept, so a change of file does not make old messages fresh again. */
void sw_auth_set_keys(sw_auth_t *a, const sw_keyring_t *keys);

/* Check message data, decoded by sw_accel_decode into s in layout, that
 * came on channel (where: the caller's count of it, for the facts).  Only
 * a message that is authentic moves its key's freshness on, so no forgery
 * can make the genuine sender's messages stale. */
sw_auth_result sw_auth_check(sw_auth_t *a, const char *channel, const void *data,
                             const swaywatch_accel_t *s, int layout, long where);

const sw_auth_facts_t *sw_auth_facts(const sw_auth_t *a);

#endif
