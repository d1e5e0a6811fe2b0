/* token.c: pbrt's lexical syntax: words, "strings", numbers, [ ], # comments. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/token.h"

bool cv_lexer_open(struct cv_lexer *lx, const char *path, struct cv_error *err)
{
    memset(lx, 0, sizeof(*lx));
    if (!cv_read_file(path, &lx->data, &lx->len, err))
        return false;
    lx->path = cv_xstrdup(path);
    lx->line = 1;
    lx->col = 1;
    return true;
}

void cv_lexer_open_string(struct cv_lexer *lx, const char *path, const char *text, size_t len)
{
    memset(lx, 0, sizeof(*lx));
    lx->data = cv_xmalloc(len + 1);
    memcpy(lx->data, text, len);
    lx->data[len] = 0;
    lx->len = len;
    lx->path = cv_xstrdup(path);
    lx->line = 1;
    lx->col = 1;
}

void cv_lexer_close(struct cv_lexer *lx)
{
    free(lx->data);
    free(lx->path);
    memset(lx, 0, sizeof(*lx));
}

static inline void advance(struct cv_lexer *lx)
{
    if (lx->data[lx->pos] == '\n') {
        lx->line++;
        lx->col = 1;
    } else {
        lx->col++;
    }
    lx->pos++;
}

static inline bool is_delim(char c)
{
    return c == 0 || c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' ||
           c == '\v' || c == '[' || c == ']' || c == '"' || c == '#';
}

static bool lex(struct cv_lexer *lx, struct cv_token *tok, struct cv_error *err)
{
    for (;;) {
        if (lx->pos >= lx->len)
            break;
        char c = lx->data[lx->pos];
        if (c == '#') {
            while (lx->pos < lx->len && lx->data[lx->pos] != '\n')
                advance(lx);
        } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
            advance(lx);
        } else {
            break;
        }
    }
    tok->file = lx->path;
    tok->line = lx->line;
    tok->col = lx->col;
    tok->text = lx->data + lx->pos;
    tok->len = 0;
    if (lx->pos >= lx->len) {
        tok->kind = CV_TOK_EOF;
        return true;
    }
    char c = lx->data[lx->pos];
    if (c == '[' || c == ']') {
        tok->kind = c == '[' ? CV_TOK_LBRACKET : CV_TOK_RBRACKET;
        tok->len = 1;
        advance(lx);
        return true;
    }
    if (c == '"') {
        advance(lx);
        size_t start = lx->pos;
        while (lx->pos < lx->len && lx->data[lx->pos] != '"') {
            if (lx->data[lx->pos] == '\n')
                return cv_fail(err, "%s:%d:%d: unterminated string (newline inside)",
                               tok->file, tok->line, tok->col);
            if (lx->data[lx->pos] == '\\' && lx->pos + 1 < lx->len)
                advance(lx);
            advance(lx);
        }
        if (lx->pos >= lx->len)
            return cv_fail(err, "%s:%d:%d: unterminated string at end of file",
                           tok->file, tok->line, tok->col);
        tok->kind = CV_TOK_STRING;
        tok->text = lx->data + start;
        tok->len = lx->pos - start;
        advance(lx);
        return true;
    }
    size_t start = lx->pos;
    while (lx->pos < lx->len && !is_delim(lx->data[lx->pos]))
        advance(lx);
    tok->len = lx->pos - start;
    if (tok->len == 0) /* a NUL byte in the input */
        return cv_fail(err, "%s:%d:%d: unexpected character", tok->file, tok->line, tok->col);
    tok->kind = (c == '-' || c == '+' || c == '.' || (c >= '0' && c <= '9')) ? CV_TOK_NUMBER
                                                                              : CV_TOK_WORD;
    return true;
}

bool cv_lexer_next(struct cv_lexer *lx, struct cv_token *tok, struct cv_error *err)
{
    if (lx->has_peek) {
        *tok = lx->peek;
        lx->has_peek = false;
        return true;
    }
    return lex(lx, tok, err);
}

bool cv_lexer_peek(struct cv_lexer *lx, struct cv_token *tok, struct cv_error *err)
{
    if (!lx->has_peek) {
        if (!lex(lx, &lx->peek, err))
            return false;
        lx->has_peek = true;
    }
    *tok = lx->peek;
    return true;
}

bool cv_token_number(const struct cv_token *tok, double *out, struct cv_error *err)
{
    char buf[64];
    if (tok->kind != CV_TOK_NUMBER || tok->len == 0 || tok->len >= sizeof(buf))
        goto bad;
    memcpy(buf, tok->text, tok->len);
    buf[tok->len] = 0;
    char *end;
    double v = strtod(buf, &end);
    if (end != buf + tok->len || !isfinite(v))
        goto bad;
    *out = v;
    return true;
bad:
    return cv_fail(err, "%s:%d:%d: bad number \"%.*s\"", tok->file, tok->line, tok->col,
                   (int)(tok->len > 40 ? 40 : tok->len), tok->text);
}

bool cv_token_is(const struct cv_token *tok, const char *word)
{
    size_t n = strlen(word);
    return tok->len == n && memcmp(tok->text, word, n) == 0;
}

char *cv_token_strdup(const struct cv_token *tok)
{
    char *s = cv_xmalloc(tok->len + 1);
    memcpy(s, tok->text, tok->len);
    s[tok->len] = 0;
    return s;
}
