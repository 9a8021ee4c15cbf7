/**
 * @file The .lsys language (lsys's grammars: the Pailou paper's notation
 * and cpfg's, which also covers cpfg `.l` files) for tree-sitter.
 *
 * The compiler's own parser is grammar/lsys.pest; this grammar follows it
 * closely enough for highlighting, folding and navigation, and accepts a
 * little more (it never has to reject a file: lsys check does that).
 *
 * Newlines end statements, except that a successor continues on an
 * indented line that does not itself start a statement. src/scanner.c
 * decides that (it looks ahead over the next line) and emits `_newline`
 * only where a statement ends.
 */

/* eslint-disable no-undef */

const PREC = {
  ternary: 1,
  or: 2,
  and: 3,
  compare: 4,
  add: 5,
  mul: 6,
  unary: 7,
  power: 8,
};

const kw = (...words) => choice(...words);
// A header keyword with its colon, as one token: `Seed(d) --> ...` is then
// a production of module `Seed`, not the `seed:` header.
const hk = (...words) => token(seq(words.length === 1 ? words[0] : choice(...words), /[ \t]*:/));

module.exports = grammar({
  name: 'lsys',

  externals: $ => [$._newline, $._error_sentinel],

  extras: $ => [/[ \t\r\uFEFF]/, /\\\r?\n/, /\n/, $.comment],

  word: $ => $.name,

  conflicts: $ => [
    [$.predecessor, $._pattern_item],
    [$.call, $.symbol],
    [$.block, $.command],
    [$.condition, $.paper_condition],
    [$.condition, $.command],
    [$.table_values, $.command],
    [$.define_item, $.macro_define],
    [$.binary, $._paper_compare],
    [$._expression, $.symbol],
  ],

  rules: {
    // Every statement ends at a newline (the scanner's) or the end of the file.
    source_file: $ => seq(
      repeat(choice(seq($._statement, $._newline), $._newline)),
      optional($._statement),
    ),

    _statement: $ => choice(
      $.define,
      $.include,
      $.preproc,
      $._header,
      $.production,
    ),

    comment: _ => token(choice(
      seq('//', /[^\n]*/),
      seq('/*', /[^*]*\*+([^/*][^*]*\*+)*/, '/'),
    )),

    // Letters of any script, digits and `_`.
    name: _ => /[\p{L}_][\p{L}\p{N}_]*/,
    number: _ => /(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?/,
    string: _ => /"([^"\\\n]|\\.)*"/,
    arrow: _ => choice('-->', '->', '−−>', '−>', '→', '⟶'),

    // ---------------------------------------------------------- directives

    define: $ => seq(
      alias(token(prec(1, seq('#', /[ \t]*/, 'define'))), '#define'),
      choice(
        commaSep1($.define_item),
        // cpfg macros often stand for module text: `#define STEM(v) !(W)F(v)`.
        prec.dynamic(-1, alias($.macro_define, $.define_item)),
      ),
    ),
    macro_define: $ => seq(
      field('name', alias($.name, $.define_name)),
      optional($.macro_parameters),
      field('value', alias($.successor, $.macro_body)),
    ),
    define_item: $ => seq(
      field('name', alias($.name, $.define_name)),
      optional(choice($.macro_parameters, $.table_dimensions)),
      optional(field('value', choice(
        $.table_values,
        $._expression,
      ))),
    ),
    macro_parameters: $ => seq(token.immediate('('), commaSep1($.name), ')'),
    table_dimensions: $ => seq(token.immediate('['), commaSep1($.table_dimension), ']'),
    table_dimension: $ => seq($._table_int, optional(seq('..', $._table_int))),
    _table_int: $ => alias(token(/[-−]?\d+/), $.number),
    table_values: $ => seq('{', optional(seq(commaSep1(choice($.table_values, $._expression)), optional(','))), '}'),

    include: $ => seq(
      alias(token(prec(1, seq('#', /[ \t]*/, 'include'))), '#include'),
      choice(
        field('path', $.string),
        field('std', $.std_name),
        commaSep1(field('component', alias($.name, $.component_name))),
      ),
    ),
    std_name: _ => /<[^>\n ]+>/,

    // cpfg's C preprocessor lines (#ifdef, #else, #endif, #undef, ...).
    preproc: $ => seq(
      field('directive', alias(token(seq('#', /[ \t]*/, /[a-z]+/)), $.directive)),
      optional(alias(/[^\n]+/, $.preproc_arg)),
    ),

    // ------------------------------------------------------------- headers

    _header: $ => choice(
      $.lsystem_header,
      $.derivation_length,
      $.axiom,
      $.context_header,
      $.expression_header,
      $.section_header,
      $.endlsystem,
      $.module_declaration,
      $.environment_header,
      $.dialect_header,
      $.colour_header,
      $.texture_header,
      $.block_header,
    ),

    lsystem_header: $ => seq(alias(hk('Lsystem', 'lsystem'), $.keyword), optional(alias(/[^\n]+/, $.label))),
    derivation_length: $ => seq(alias(hk(/[Dd]erivation[ \t]+[Ll]ength/), $.keyword), $._expression),
    axiom: $ => seq(alias(hk('Axiom', 'axiom', 'ω', 'Ω'), $.keyword), optional($.successor)),
    context_header: $ => seq(
      alias(hk(/#?[Ii]gnore/, /#?[Cc]onsider/), $.keyword),
      repeat(choice($._pattern_symbol, $.branch, $.roll)),
    ),
    expression_header: $ => seq(
      alias(hk(/[Ss]eed/, /[Aa]ngle/, /[Ss]tep/, /[Ww]idth/, /[Mm]aximum[ \t]+[Dd]epth/), $.keyword),
      $._expression,
    ),
    section_header: $ => seq(
      alias(kw('homomorphism', 'Homomorphism', 'decomposition', 'Decomposition'), $.keyword),
      optional(seq(':', optional(alias(/[^\n]+/, $.label)))),
    ),
    endlsystem: $ => alias(kw('endlsystem', 'Endlsystem'), $.keyword),
    module_declaration: $ => seq(
      alias(kw('module', 'Module'), $.keyword),
      optional(':'),
      commaSep1($.module_declarator),
    ),
    module_declarator: $ => seq(field('name', $.symbol), optional($.macro_parameters)),
    environment_header: $ => seq(alias(hk(/[Ee]nvironment/), $.keyword), optional(alias(/[^\n]+/, $.environment_program))),
    dialect_header: $ => seq(alias(hk(/[Dd]ialect/), $.keyword), alias($.name, $.dialect_name)),
    colour_header: $ => seq(alias(kw('colour', 'Colour', 'color', 'Color'), $.keyword), $._expression, ':', $.hex_colour),
    hex_colour: _ => /#[0-9a-fA-F]{6}/,
    texture_header: $ => seq(alias(kw('texture', 'Texture'), $.keyword), $._expression, ':', field('path', $.string)),
    // Wins over the paper's form `Start : { ...`, which would also parse.
    block_header: $ => prec.dynamic(10, seq(
      alias(hk(/[Ss]tart/, /[Ss]tartEach/, /[Ee]nd/, /[Ee]ndEach/, /[Dd]efine/), $.keyword),
      $.block,
    )),

    // --------------------------------------------------------- productions

    production: $ => seq(
      $._head,
      choice(
        // Wins over the paper's form, which can also read `x < N --> F` as
        // modules `x < N - - > F`.
        prec.dynamic(5, seq(
          optional(seq(':', optional($.block), optional($.condition), optional($.block))),
          $.arrow,
          optional($.successor),
          optional(seq(':', field('probability', $._expression))),
        )),
        // The paper's arrowless form: `pred : [condition] successor`.
        seq(':', optional(alias($.paper_condition, $.condition)), optional($.successor)),
      ),
    ),
    _head: $ => seq(
      optional(seq(field('left', $.left_context), '<')),
      field('predecessor', $.predecessor),
      optional(seq('>', field('right', $.right_context))),
    ),
    left_context: $ => repeat1($._pattern_item),
    predecessor: $ => repeat1(alias($.pattern_module, $.module)),
    right_context: $ => repeat1($._pattern_item),
    _pattern_item: $ => choice(alias($.pattern_module, $.module), alias('[', $.branch), alias(']', $.branch)),
    pattern_module: $ => seq(field('name', $._pattern_symbol), optional($.parameters)),
    parameters: $ => seq(token.immediate('('), optional(commaSep1($._expression)), ')'),

    condition: $ => choice('else', '*', $._expression),
    // Without an arrow a condition is comparisons joined by and/or.
    paper_condition: $ => prec.dynamic(1, choice('else', $._paper_compare)),
    _paper_compare: $ => choice(
      prec.left(PREC.compare, seq($._expression, choice('<', '>', '<=', '>=', '==', '!=', '≤', '≥', '≠'), $._expression)),
      prec.left(PREC.and, seq($._paper_compare, choice('&&', 'and', '∧', '||', 'or', '∨'), $._paper_compare)),
    ),

    // ------------------------------------------------------------ modules

    successor: $ => repeat1($.module),
    module: $ => seq(field('name', $._symbol), optional($.arguments)),
    arguments: $ => seq(token.immediate('('), optional(commaSep1(choice($.string, $._expression))), ')'),

    _symbol: $ => choice($.symbol, $.command, $.component, $.query, $.branch, $.roll),
    _pattern_symbol: $ => choice($.symbol, $.command, $.component, $.query),
    symbol: $ => choice($.name, alias(/\d[\p{L}\p{N}_]*/, $.name)),
    command: _ => choice(
      /@[\p{L}\p{N}_]*/,
      '+', '-', '−', '&', '^', '∧', '/', '\\', '|', '$', '%', '!', ';', ',', "'", '{', '}', '.', '=', '#', '*', '"', '`',
    ),
    component: _ => /[~∼][\p{L}\p{N}_]+/,
    query: _ => /\?[\p{L}\p{N}_]*/,
    branch: _ => choice('[', ']'),
    // `<` and `>` roll the turtle in a successor (the paper's notation).
    roll: _ => choice('<', '>'),

    // --------------------------------------------------------- expressions

    _expression: $ => choice(
      $.number,
      $.name,
      $.call,
      $.index,
      $.parenthesized,
      $.unary,
      $.binary,
      $.ternary,
    ),
    parenthesized: $ => seq('(', $._expression, ')'),
    call: $ => seq(field('function', $.name), alias($.arguments, $.arguments)),
    index: $ => prec(1, seq(field('table', $.name), repeat1(seq(token.immediate('['), commaSep1($._expression), ']')))),
    unary: $ => prec(PREC.unary, seq(choice('-', '−', '+', '!', 'not', '\\'), $._expression)),
    binary: $ => choice(
      prec.right(PREC.power, seq($._expression, choice('^', '**'), $._expression)),
      ...[
        [PREC.mul, choice('*', '/', '%')],
        [PREC.add, choice('+', '-', '−')],
        [PREC.compare, choice('<', '>', '<=', '>=', '==', '!=', '≤', '≥', '≠')],
        [PREC.and, choice('&&', 'and', '∧')],
        [PREC.or, choice('||', 'or', '∨')],
      ].map(([p, op]) => prec.left(p, seq($._expression, op, $._expression))),
    ),
    ternary: $ => prec.right(PREC.ternary, seq($._expression, '?', $._expression, ':', $._expression)),

    // ------------------------------------------------- cpfg statement blocks

    block: $ => seq('{', repeat($._c_statement), '}'),
    _c_statement: $ => choice($.if_statement, $.while_statement, $.do_statement, $.array_statement, $.assignment, $.expression_statement, ';'),
    _c_body: $ => choice($.block, $._c_statement),
    if_statement: $ => prec.right(seq('if', '(', $._expression, ')', $._c_body, optional(seq('else', $._c_body)))),
    while_statement: $ => seq('while', '(', $._expression, ')', $._c_body),
    do_statement: $ => seq('do', $._c_body, 'while', '(', $._expression, ')', ';'),
    array_statement: $ => seq('array', commaSep1($.array_declarator), ';'),
    array_declarator: $ => seq($.name, repeat1(seq('[', $._expression, ']')), optional(seq('=', $.initializer))),
    initializer: $ => seq('{', optional(seq(commaSep1(choice($.initializer, $._expression)), optional(','))), '}'),
    assignment: $ => seq(field('left', choice($.name, $.index)), choice('=', '+=', '-=', '*=', '/='), $._expression, ';'),
    expression_statement: $ => seq($._expression, ';'),
  },
});

function commaSep1(rule) {
  return seq(rule, repeat(seq(',', rule)));
}
