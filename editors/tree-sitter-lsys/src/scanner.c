// External scanner for tree-sitter-lsys: decides whether a newline ends a
// statement. A successor continues on an indented line that does not start
// a statement of its own (grammar/lsys.pest's `cont`): the scanner looks
// ahead over the next non-blank line to tell the two apart. Only the
// newline itself becomes the token; the look-ahead is not consumed.

#include "tree_sitter/parser.h"

#include <stdbool.h>
#include <stdint.h>

enum TokenType { NEWLINE, ERROR_SENTINEL };

void *tree_sitter_lsys_external_scanner_create(void) { return NULL; }
void tree_sitter_lsys_external_scanner_destroy(void *payload) { (void)payload; }
unsigned tree_sitter_lsys_external_scanner_serialize(void *payload, char *buffer) {
  (void)payload;
  (void)buffer;
  return 0;
}
void tree_sitter_lsys_external_scanner_deserialize(void *payload, const char *buffer, unsigned length) {
  (void)payload;
  (void)buffer;
  (void)length;
}

static bool is_blank(int32_t c) { return c == ' ' || c == '\t' || c == '\r'; }

// Skips a `/* ... */` comment whose `/` has been seen and `*` is next.
static void skip_block_comment(TSLexer *lexer) {
  lexer->advance(lexer, false);
  int32_t prev = 0;
  while (!lexer->eof(lexer)) {
    int32_t c = lexer->lookahead;
    lexer->advance(lexer, false);
    if (prev == '*' && c == '/') return;
    prev = c;
  }
}

// Whether an arrow starts here: -->, ->, −−>, −>, →, ⟶ (consumes what it reads).
static bool arrow_here(TSLexer *lexer) {
  int32_t c = lexer->lookahead;
  if (c == 0x2192 || c == 0x27F6) return true;
  if (c == '-' || c == 0x2212) {
    lexer->advance(lexer, false);
    if (lexer->lookahead == '-' || lexer->lookahead == 0x2212) lexer->advance(lexer, false);
    return lexer->lookahead == '>';
  }
  return false;
}

// The rest of an indented line: does it start a statement? It does when it
// begins with a directive (`#` and a word), or has an arrow, `=>` or a `:` outside parentheses
// (a production, a header); it does not when it begins with an arrow or
// `:` (the head above continues).
static bool line_starts_statement(TSLexer *lexer) {
  int32_t c = lexer->lookahead;
  if (c == '#') {
    // `#define`, `#ifdef`, ... start a statement; `#(1.0)` is a module.
    lexer->advance(lexer, false);
    while (is_blank(lexer->lookahead)) lexer->advance(lexer, false);
    c = lexer->lookahead;
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) return true;
  }
  if (c == ':' || c == 0x2192 || c == 0x27F6) return false;
  if (c == '-' || c == 0x2212) {
    if (arrow_here(lexer)) return false;
  }
  int depth = 0;
  while (!lexer->eof(lexer) && lexer->lookahead != '\n') {
    c = lexer->lookahead;
    if (c == '(') depth++;
    else if (c == ')' && depth > 0) depth--;
    else if (c == ':' && depth == 0) return true;
    else if (c == '/') {
      lexer->advance(lexer, false);
      if (lexer->lookahead == '/' ) return false;
      if (lexer->lookahead == '*') {
        skip_block_comment(lexer);
      }
      continue;
    } else if (c == '=') {
      lexer->advance(lexer, false);
      if (lexer->lookahead == '>') return true;
      continue;
    } else if (arrow_here(lexer)) {
      return true;
    } else if (c == '-' || c == 0x2212) {
      continue;  // arrow_here consumed a `-` that was not an arrow
    }
    lexer->advance(lexer, false);
  }
  return false;
}

bool tree_sitter_lsys_external_scanner_scan(void *payload, TSLexer *lexer, const bool *valid_symbols) {
  (void)payload;
  // During error recovery every symbol is valid: let the grammar's own
  // lexer take the newline as white space.
  if (valid_symbols[ERROR_SENTINEL] || !valid_symbols[NEWLINE]) return false;
  while (is_blank(lexer->lookahead)) lexer->advance(lexer, true);
  if (lexer->lookahead != '\n') return false;
  lexer->advance(lexer, false);
  lexer->mark_end(lexer);
  lexer->result_symbol = NEWLINE;
  // Look over blank and comment-only lines for the next line with text.
  for (;;) {
    if (lexer->eof(lexer)) return true;
    bool indented = false;
    while (is_blank(lexer->lookahead)) {
      if (lexer->lookahead != '\r') indented = true;
      lexer->advance(lexer, false);
    }
    int32_t c = lexer->lookahead;
    if (c == '\n') {
      lexer->advance(lexer, false);
      continue;
    }
    if (c == '/') {
      lexer->advance(lexer, false);
      if (lexer->lookahead == '/') {
        while (!lexer->eof(lexer) && lexer->lookahead != '\n') lexer->advance(lexer, false);
        continue;
      }
      if (lexer->lookahead == '*') {
        skip_block_comment(lexer);
        while (is_blank(lexer->lookahead)) lexer->advance(lexer, false);
        if (lexer->lookahead == '\n') continue;
      }
      // Text after a comment on that line: decide on the line.
      if (!indented) return true;
      return line_starts_statement(lexer);
    }
    if (!indented) return true;
    return line_starts_statement(lexer);
  }
}
