/*
 * scene_lexer.c - the scene loader's errors and tokens: scene_fail() and the way
 * messages quote a token, and the lexer that cuts the text into words,
 * quoted strings and ends of line with their line and column (GNU columns:
 * characters, tabs to the next multiple of 8).  Bytes that are not UTF-8
 * text are an error here, so nothing later sees them.
 */
#include "scene_parser.h"

#include <stdarg.h>
#include <string.h>

#define TAB_WIDTH 8 /* GNU columns: a tab moves to the next multiple of 8, plus 1 */

bool
scene_fail(struct parser *p, const struct token *at, const char *fmt, ...)
{
    char msg[sizeof p->err->msg];  // sizeof does not evaluate: p->err may be NULL
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag_set(p->err, p->name, at->line, at->col, "%s", msg);
    return false;
}

struct shown
scene_show(const struct token *t)
{
    struct shown out;
    if (t->kind == TOK_EOL || t->kind == TOK_EOF) {
        snprintf(out.s, sizeof out.s, "end of line");
        return out;
    }
    size_t n = t->len;
    const char *more = "";
    if (n > MAX_SHOWN) {
        n = MAX_SHOWN;
        while (n > 0 && ((unsigned char)t->text[n] & 0xc0) == 0x80) {
            n--;  // do not cut a UTF-8 character in two
        }
        more = "...";
    }
    snprintf(out.s, sizeof out.s, "'%.*s%s'", (int)n, t->text, more);
    return out;
}

bool
scene_token_is(const struct token *t, const char *word)
{
    return t->kind == TOK_WORD && strlen(word) == t->len && memcmp(t->text, word, t->len) == 0;
}

struct src_loc
scene_loc_of(const struct token *t)
{
    return (struct src_loc){.line = t->line, .col = t->col};
}

/* --- Lexer ---------------------------------------------------------------- */

static struct token
here(const struct parser *p)
{
    return (struct token){.text = p->src + p->pos, .line = p->line, .col = p->col};
}

/* Bytes in the character at p->pos: 1 for a tab or printable ASCII, 2 to 4
 * for valid UTF-8, 0 for anything a text file should not hold. */
static int
char_bytes(const struct parser *p)
{
    const unsigned char *s = (const unsigned char *)p->src + p->pos;
    unsigned c = s[0];
    if (c == '\t' || (c >= 0x20 && c < 0x7f)) {
        return 1;
    }
    int n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : 2;
    if (c < 0xc2 || c > 0xf4 || (size_t)n > p->len - p->pos) {
        return 0;
    }
    unsigned cp = c & (0x7fu >> n);
    for (int i = 1; i < n; i++) {
        if ((s[i] & 0xc0) != 0x80) {
            return 0;
        }
        cp = cp << 6 | (s[i] & 0x3fu);
    }
    static const unsigned min_cp[5] = {0, 0, 0x80, 0x800, 0x10000};  // below: overlong
    bool surrogate = cp >= 0xd800 && cp <= 0xdfff;
    return cp < min_cp[n] || cp > 0x10ffff || surrogate ? 0 : n;
}

/* Step over one character; the column counts characters, not bytes.  A
 * byte-order mark is invisible in an editor and in a message: one past the
 * file's start (skipped there) is named, not shown. */
static bool
advance(struct parser *p)
{
    int n = char_bytes(p);
    if (n == 0) {
        struct token at = here(p);
        return scene_fail(p, &at, "unexpected byte 0x%02x", (unsigned char)p->src[p->pos]);
    }
    if (n == 3 && memcmp(p->src + p->pos, "\xEF\xBB\xBF", 3) == 0) {
        struct token at = here(p);
        return scene_fail(
            p,
            &at,
            "an invisible byte-order mark (U+FEFF, bytes EF BB BF) inside the file (files "
            "joined?): only the file's first bytes may hold one; delete it");
    }
    bool tab = p->src[p->pos] == '\t';
    p->col = tab ? ((p->col - 1) / TAB_WIDTH + 1) * TAB_WIDTH + 1 : p->col + 1;
    p->pos += (size_t)n;
    return true;
}

static bool
at_line_end(const struct parser *p)
{
    size_t i = p->pos;
    if (i == p->len) {
        return true;
    }
    return p->src[i] == '\n' || (p->src[i] == '\r' && (i + 1 == p->len || p->src[i + 1] == '\n'));
}

/* A word ends at a space, a tab, a comment or the end of the line. */
static bool
at_word_end(const struct parser *p)
{
    return at_line_end(p) || p->src[p->pos] == ' ' || p->src[p->pos] == '\t'
           || p->src[p->pos] == '#';
}

static bool
lex_string(struct parser *p, struct token *tok)
{
    tok->kind = TOK_STRING;
    advance(p);
    for (;;) {
        if (at_line_end(p)) {
            return scene_fail(p, tok, "unterminated quoted string");
        }
        const char *c = p->src + p->pos;
        if (c[0] == '"') {
            break;
        }
        bool escape = c[0] == '\\' && p->pos + 1 < p->len && (c[1] == '"' || c[1] == '\\');
        if ((escape && !advance(p)) || !advance(p)) {
            return false;
        }
    }
    advance(p);
    tok->len = (size_t)(p->src + p->pos - tok->text);
    struct token after = here(p);
    return at_word_end(p) || scene_fail(p, &after, "expected a space after the closing quote");
}

static bool
lex_word(struct parser *p, struct token *tok)
{
    tok->kind = TOK_WORD;
    while (!at_word_end(p)) {
        if (p->src[p->pos] == '"') {
            struct token at = here(p);
            return scene_fail(p, &at, "unexpected '\"' inside a word (quote the whole file name)");
        }
        if (!advance(p)) {
            return false;
        }
    }
    tok->len = (size_t)(p->src + p->pos - tok->text);
    return true;
}

/* The next token: comments are skipped, each line ends with a TOK_EOL and
 * the text with a TOK_EOF (returned again by every later call). */
bool
scene_next_token(struct parser *p, struct token *tok)
{
    while (p->pos < p->len && (p->src[p->pos] == ' ' || p->src[p->pos] == '\t')) {
        advance(p);
    }
    while (p->pos < p->len && p->src[p->pos] == '#' && !at_line_end(p)) {
        do {
            if (!advance(p)) {  // a comment, too, must be text
                return false;
            }
        } while (!at_line_end(p));
    }
    *tok = here(p);
    if (p->pos == p->len) {
        tok->kind = TOK_EOF;
        return true;
    }
    if (at_line_end(p)) {
        tok->kind = TOK_EOL;
        p->pos += p->src[p->pos] == '\r' ? 1 : 0;
        p->pos += p->pos < p->len ? 1 : 0;
        p->line++;
        p->col = 1;
        return true;
    }
    return p->src[p->pos] == '"' ? lex_string(p, tok) : lex_word(p, tok);
}

bool
scene_peek_token(struct parser *p, struct token *tok)
{
    size_t pos = p->pos;
    int line = p->line;
    int col = p->col;
    bool ok = scene_next_token(p, tok);
    p->pos = pos;
    p->line = line;
    p->col = col;
    return ok;
}
