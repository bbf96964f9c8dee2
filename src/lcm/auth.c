/* SPDX-License-Identifier: GPL-3.0-or-later */
/* auth.c - authenticated accel_t samples (auth.h): key files parsed, MACs
 * made and checked with libsodium's HMAC-SHA-256, the freshness seen under
 * each key, and the two layouts of the accel channel decoded.
 *
 * Each key's HMAC state is keyed once, when the file is read (the inner
 * and outer pads hashed): a message then costs a copy of that state and
 * the hash of its own 60 to 120 bytes, with no allocation. */
#include "auth.h"

#include <ctype.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "swaywatch/status.h"
#include "swaywatch_accel_v1_t.h"

struct sw_keyring {
    int n;
    uint8_t order[SW_AUTH_ID_MAX];    /* ids in file order */
    int line[SW_AUTH_ID_MAX + 1];     /* per id: the line it is on, 0 = none */
    crypto_auth_hmacsha256_state *st; /* per id: HMAC keyed with it */
};

struct sw_auth {
    const sw_keyring_t *keys;
    int64_t last[SW_AUTH_ID_MAX + 1]; /* the highest freshness accepted under each id */
    uint8_t seen[SW_AUTH_ID_MAX + 1];
    sw_auth_facts_t f;
};

_Static_assert(sizeof(((swaywatch_accel_t *)0)->mac) == SW_AUTH_MAC_LEN,
               "accel_t.mac holds the truncated MAC");
_Static_assert(SW_AUTH_MAC_LEN <= crypto_auth_hmacsha256_BYTES, "a MAC is truncated, not padded");

static const char *const result_names[SW_AUTH_NRESULTS] = {"ok", "unauthenticated", "unknown_key",
                                                           "bad_mac", "replayed"};
static const char *const result_texts[SW_AUTH_NRESULTS] = {
    "authentic", "no MAC", "a key id that is not in the key file", "a MAC that does not match",
    "a copy of an earlier message (freshness not above the last)"};

const char *sw_auth_result_name(sw_auth_result r)
{
    return (unsigned)r < SW_AUTH_NRESULTS ? result_names[r] : "unknown";
}

const char *sw_auth_result_text(sw_auth_result r)
{
    return (unsigned)r < SW_AUTH_NRESULTS ? result_texts[r] : "unknown";
}

/* ---- key files ------------------------------------------------------------------ */

#define LINE_MAX_KEYS 512 /* bytes of a key line we look at */

static int fail(char *msg, size_t msglen, const char *name, int line, const char *what)
{
    if (msg)
        snprintf(msg, msglen, "%s:%d: %s", name, line, what);
    return -1;
}

/* The next whitespace-separated word of *p (NUL-terminated in place), or
 * NULL at the end. */
static char *word(char **p)
{
    char *s = *p;
    while (*s == ' ' || *s == '\t') s++;
    if (!*s)
        return NULL;
    char *w = s;
    while (*s && *s != ' ' && *s != '\t') s++;
    if (*s)
        *s++ = '\0';
    *p = s;
    return w;
}

/* One line (NUL-terminated, no newline) into k: 0, or -1 with msg. */
static int parse_line(sw_keyring_t *k, char *s, const char *name, int ln, char *msg, size_t msglen)
{
    char *p = s;
    char *id_s = word(&p);
    if (!id_s || id_s[0] == '#')
        return 0; /* blank or a comment */
    char *type = word(&p), *key = word(&p), *extra = word(&p);
    if (!type || !key || extra)
        return fail(msg, msglen, name, ln,
                    "expected 'ID " SW_AUTH_TYPE
                    " HEX:KEY' (ID 1 to 255, KEY 64 hexadecimal "
                    "digits, as swaywatch keygen writes)");
    char why[160];
    long id = 0;
    int digits = 0;
    for (const char *c = id_s; *c; c++, digits++) {
        if (!isdigit((unsigned char)*c) || digits >= 4) {
            id = -1;
            break;
        }
        id = id * 10 + (*c - '0');
    }
    if (id < 1 || id > SW_AUTH_ID_MAX) {
        snprintf(why, sizeof why, "key id '%.8s' is not a whole number from 1 to %d", id_s,
                 SW_AUTH_ID_MAX);
        return fail(msg, msglen, name, ln, why);
    }
    if (k->line[id]) {
        snprintf(why, sizeof why, "key id %ld is given twice (line %d and here)", id, k->line[id]);
        return fail(msg, msglen, name, ln, why);
    }
    if (strcasecmp(type, SW_AUTH_TYPE) != 0) {
        snprintf(why, sizeof why, "key type '%.20s': only " SW_AUTH_TYPE " is known", type);
        return fail(msg, msglen, name, ln, why);
    }
    /* the key is never quoted back: it is a secret */
    uint8_t bin[SW_AUTH_KEY_LEN];
    size_t binlen = 0;
    const char *end = NULL;
    const size_t hexlen = strlen(key) > 4 ? strlen(key) - 4 : 0;
    if (strncasecmp(key, "HEX:", 4) != 0 || hexlen != 2 * SW_AUTH_KEY_LEN ||
        sodium_hex2bin(bin, sizeof bin, key + 4, hexlen, NULL, &binlen, &end) != 0 ||
        binlen != SW_AUTH_KEY_LEN || end != key + 4 + hexlen) {
        sodium_memzero(bin, sizeof bin);
        sodium_memzero(key, strlen(key));
        return fail(msg, msglen, name, ln,
                    "the key is not HEX: and 64 hexadecimal digits (32 bytes, as swaywatch "
                    "keygen writes)");
    }
    crypto_auth_hmacsha256_init(&k->st[id], bin, sizeof bin);
    sodium_memzero(bin, sizeof bin);
    sodium_memzero(key, strlen(key));
    k->line[id] = ln;
    k->order[k->n++] = (uint8_t)id;
    return 0;
}

sw_keyring_t *sw_keyring_parse(const char *text, size_t len, const char *name, char *msg,
                               size_t msglen)
{
    if (!name)
        name = "key file";
    if (msg && msglen)
        msg[0] = '\0';
    if (sodium_init() < 0) {
        if (msg)
            snprintf(msg, msglen, "%s: libsodium could not be initialised", name);
        return NULL;
    }
    if (!text || len > SW_AUTH_FILE_MAX) {
        if (msg)
            snprintf(msg, msglen, "%s: longer than %d bytes: not a key file", name,
                     SW_AUTH_FILE_MAX);
        return NULL;
    }
    sw_keyring_t *k = calloc(1, sizeof *k);
    if (k)
        k->st = calloc(SW_AUTH_ID_MAX + 1, sizeof *k->st);
    if (!k || !k->st) {
        if (msg)
            snprintf(msg, msglen, "%s: %s", name, sw_strerror(SW_ENOMEM));
        sw_keyring_destroy(k);
        return NULL;
    }
    char line[LINE_MAX_KEYS + 1];
    size_t at = 0;
    int ln = 0;
    while (at < len) {
        ln++;
        size_t e = at;
        while (e < len && text[e] != '\n') e++;
        size_t n = e - at;
        if (n && text[at + n - 1] == '\r')
            n--; /* CRLF */
        int bad = 0;
        if (memchr(text + at, '\0', n))
            bad = fail(msg, msglen, name, ln, "a NUL byte: not a key file");
        else if (n > LINE_MAX_KEYS)
            bad = fail(msg, msglen, name, ln, "line too long for a key line");
        if (!bad) {
            memcpy(line, text + at, n);
            line[n] = '\0';
            bad = parse_line(k, line, name, ln, msg, msglen);
            sodium_memzero(line, sizeof line);
        }
        if (bad) {
            sw_keyring_destroy(k);
            return NULL;
        }
        at = e + 1;
    }
    if (k->n == 0) {
        if (msg)
            snprintf(msg, msglen,
                     "%s: no key in it (a key line is 'ID " SW_AUTH_TYPE
                     " HEX:KEY'; swaywatch keygen writes one)",
                     name);
        sw_keyring_destroy(k);
        return NULL;
    }
    return k;
}

void sw_keyring_destroy(sw_keyring_t *k)
{
    if (!k)
        return;
    if (k->st) {
        sodium_memzero(k->st, (SW_AUTH_ID_MAX + 1) * sizeof *k->st);
        free(k->st);
    }
    free(k);
}

int sw_keyring_size(const sw_keyring_t *k)
{
    return k ? k->n : 0;
}

int sw_keyring_id(const sw_keyring_t *k, int i)
{
    return k && i >= 0 && i < k->n ? k->order[i] : 0;
}

int sw_keyring_has(const sw_keyring_t *k, int id)
{
    return k && id >= 1 && id <= SW_AUTH_ID_MAX && k->line[id] != 0;
}

int sw_keyring_signer(const sw_keyring_t *k)
{
    return k && k->n ? k->order[k->n - 1] : 0;
}

/* ---- MACs ----------------------------------------------------------------------- */

int sw_auth_mac(const sw_keyring_t *k, int id, const char *channel, const uint8_t *head,
                uint8_t mac[SW_AUTH_MAC_LEN])
{
    if (!sw_keyring_has(k, id))
        return SW_ENOTFOUND;
    static const uint8_t nul = 0;
    crypto_auth_hmacsha256_state st = k->st[id]; /* keyed when the file was read */
    uint8_t full[crypto_auth_hmacsha256_BYTES];
    crypto_auth_hmacsha256_update(&st, (const uint8_t *)channel, strlen(channel));
    crypto_auth_hmacsha256_update(&st, &nul, 1);
    crypto_auth_hmacsha256_update(&st, head, SW_AUTH_HEAD_LEN);
    crypto_auth_hmacsha256_final(&st, full);
    memcpy(mac, full, SW_AUTH_MAC_LEN);
    sodium_memzero(&st, sizeof st);
    return SW_OK;
}

int sw_auth_sign(const sw_keyring_t *k, int id, const char *channel, swaywatch_accel_t *msg)
{
    if (!sw_keyring_has(k, id))
        return SW_ENOTFOUND;
    uint8_t buf[SW_AUTH_ACCEL_LEN];
    msg->key_id = (uint8_t)id;
    if (swaywatch_accel_t_encode(buf, 0, sizeof buf, msg) != SW_AUTH_ACCEL_LEN)
        return SW_EINVAL;
    uint8_t mac[SW_AUTH_MAC_LEN];
    sw_auth_mac(k, id, channel, buf, mac);
    memcpy(msg->mac, mac, sizeof mac);
    return SW_OK;
}

/* ---- messages ------------------------------------------------------------------- */

int sw_accel_decode(const void *data, size_t len, swaywatch_accel_t *s, int *layout)
{
    if (len > INT32_MAX)
        return -1;
    int used = swaywatch_accel_t_decode(data, 0, (int)len, s);
    if (used >= 0) {
        *layout = 2;
        return used;
    }
    swaywatch_accel_v1_t v;
    used = swaywatch_accel_v1_t_decode(data, 0, (int)len, &v);
    if (used < 0)
        return -1;
    memset(s, 0, sizeof *s);
    s->utime = v.utime;
    s->seq = v.seq;
    s->ax = v.ax;
    s->ay = v.ay;
    s->az = v.az;
    *layout = 1;
    return used;
}

/* ---- the verifier --------------------------------------------------------------- */

sw_auth_t *sw_auth_create(const sw_keyring_t *keys)
{
    if (sodium_init() < 0)
        return NULL;
    sw_auth_t *a = calloc(1, sizeof *a);
    if (a)
        a->keys = keys;
    return a;
}

void sw_auth_destroy(sw_auth_t *a)
{
    free(a);
}

void sw_auth_set_keys(sw_auth_t *a, const sw_keyring_t *keys)
{
    a->keys = keys;
}

static sw_auth_result verdict(sw_auth_t *a, const char *channel, const void *data,
                              const swaywatch_accel_t *s, int layout)
{
    if (layout != 2 || s->key_id == 0)
        return SW_AUTH_NONE;
    if (!sw_keyring_has(a->keys, s->key_id))
        return SW_AUTH_UNKNOWN_KEY;
    uint8_t mac[SW_AUTH_MAC_LEN];
    sw_auth_mac(a->keys, s->key_id, channel, data, mac);
    if (sodium_memcmp(mac, s->mac, SW_AUTH_MAC_LEN) != 0)
        return SW_AUTH_BAD_MAC;
    if (a->seen[s->key_id] && s->freshness <= a->last[s->key_id])
        return SW_AUTH_REPLAYED;
    a->seen[s->key_id] = 1;
    a->last[s->key_id] = s->freshness;
    return SW_AUTH_OK;
}

sw_auth_result sw_auth_check(sw_auth_t *a, const char *channel, const void *data,
                             const swaywatch_accel_t *s, int layout, long where)
{
    const sw_auth_result r = verdict(a, channel, data, s, layout);
    a->f.checked++;
    a->f.refused[r]++;
    if (r != SW_AUTH_OK) {
        sw_auth_place_t p = {.where = where, .key_id = layout == 2 ? s->key_id : 0, .why = r};
        snprintf(p.channel, sizeof p.channel, "%s", channel);
        if (a->f.first.why == SW_AUTH_OK)
            a->f.first = p;
        a->f.last = p;
    }
    return r;
}

const sw_auth_facts_t *sw_auth_facts(const sw_auth_t *a)
{
    return &a->f;
}
