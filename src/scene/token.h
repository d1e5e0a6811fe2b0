/* token.h: the pbrt tokenizer. It reads one file into memory once and hands
 * out tokens that point into that buffer (no copies), each with its
 * file:line:col (1-based) for messages. */
#ifndef CV_SCENE_TOKEN_H
#define CV_SCENE_TOKEN_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

enum cv_tok_kind {
    CV_TOK_EOF,
    CV_TOK_WORD,     /* directive names, bare true/false */
    CV_TOK_STRING,   /* text excludes the quotes */
    CV_TOK_NUMBER,   /* text as written; see cv_token_number */
    CV_TOK_LBRACKET,
    CV_TOK_RBRACKET,
};

struct cv_token {
    enum cv_tok_kind kind;
    const char *text;  /* into the lexer's buffer; not NUL-terminated */
    size_t len;
    const char *file;  /* the lexer's path; lives as long as the lexer */
    int line, col;
};

struct cv_lexer {
    char *path;
    char *data;        /* whole file, NUL-terminated */
    size_t len, pos;
    int line, col;
    bool has_peek;
    struct cv_token peek;
    size_t directives; /* read from this file so far (the parser counts) */
};

/* Opens path; on failure err names the path. */
bool cv_lexer_open(struct cv_lexer *lx, const char *path, struct cv_error *err);
/* Tokenizes a caller-owned string (copied); path is for messages. */
void cv_lexer_open_string(struct cv_lexer *lx, const char *path, const char *text, size_t len);
void cv_lexer_close(struct cv_lexer *lx);
/* Next token (EOF at the end, repeatedly). False on a lexical error
 * (unterminated string, stray character), with file:line:col in err. */
bool cv_lexer_next(struct cv_lexer *lx, struct cv_token *tok, struct cv_error *err);
bool cv_lexer_peek(struct cv_lexer *lx, struct cv_token *tok, struct cv_error *err);

/* Parses a NUMBER token fully; false (with location) if it is not a finite number. */
bool cv_token_number(const struct cv_token *tok, double *out, struct cv_error *err);
bool cv_token_is(const struct cv_token *tok, const char *word);
/* Newly allocated NUL-terminated copy of the text. */
char *cv_token_strdup(const struct cv_token *tok);

#endif
