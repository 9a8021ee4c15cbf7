; Highlights for .lsys grammars and cpfg .l models. Capture names follow
; nvim-treesitter's (Helix: see README.md for the few it names differently).

(comment) @comment
(string) @string
(number) @number
(hex_colour) @string.special
(std_name) @string.special.path

(keyword) @keyword
(label) @label
(environment_program) @string
(dialect_name) @constant.builtin

["#define" "#include"] @keyword.directive
(preproc (directive) @keyword.directive)
(preproc (preproc_arg) @constant.macro)

["if" "while" "do" "array"] @keyword.conditional
(if_statement "else" @keyword.conditional)
(condition "else" @keyword)
(condition "*" @keyword)

(arrow) @operator
(binary ["+" "-" "−" "*" "/" "%" "^" "**" "<" ">" "<=" ">=" "==" "!=" "≤" "≥" "≠" "&&" "||" "and" "or" "∧" "∨"] @operator)
(unary ["-" "−" "+" "!" "not"] @operator)
(ternary ["?" ":"] @operator)
(condition ["<" ">" "<=" ">=" "==" "!=" "≤" "≥" "≠" "&&" "||" "and" "or" "∧" "∨"] @operator)
(assignment ["=" "+=" "-=" "*=" "/="] @operator)

; Defines, their uses in expressions are plain names.
(define_item name: (define_name) @constant.macro)
(macro_parameters (name) @variable.parameter)
(include component: (component_name) @type)

; Modules: the predecessor is the definition; turtle commands written as
; letters (F f G g ...) are built in. Each pattern excludes the others'
; names, so editors that let the first match win (Helix, tree-sitter
; highlight) and those that let the last win (Neovim) agree.
((symbol) @function.builtin
  (#match? @function.builtin "^[FfGgHhLlRrTtZz]$"))
(predecessor (module name: (symbol) @function
  (#not-match? @function "^[FfGgHhLlRrTtZz]$")))
(left_context (module name: (symbol) @function.call
  (#not-match? @function.call "^[FfGgHhLlRrTtZz]$")))
(right_context (module name: (symbol) @function.call
  (#not-match? @function.call "^[FfGgHhLlRrTtZz]$")))
(successor (module name: (symbol) @function.call
  (#not-match? @function.call "^[FfGgHhLlRrTtZz]$")))
(module_declarator name: (symbol) @function)

(command) @function.builtin
(branch) @punctuation.bracket
(roll) @function.builtin
(component) @type
(query) @function.builtin

; Formal parameters in a predecessor or context.
(parameters (name) @variable.parameter)

(call function: (name) @function.call)
(index table: (name) @variable)

["(" ")" "{" "}"] @punctuation.bracket
;; Separators (not `,` `;` as turtle commands in a successor).
[
  (arguments "," @punctuation.delimiter)
  (parameters "," @punctuation.delimiter)
  (macro_parameters "," @punctuation.delimiter)
  (define "," @punctuation.delimiter)
  (include "," @punctuation.delimiter)
  (table_values "," @punctuation.delimiter)
  (table_dimensions "," @punctuation.delimiter)
  (initializer "," @punctuation.delimiter)
  (module_declaration ["," ":"] @punctuation.delimiter)
  (array_statement ["," ";"] @punctuation.delimiter)
  (production ":" @punctuation.delimiter)
  (colour_header ":" @punctuation.delimiter)
  (texture_header ":" @punctuation.delimiter)
  (section_header ":" @punctuation.delimiter)
  (block ";" @punctuation.delimiter)
  (assignment ";" @punctuation.delimiter)
  (expression_statement ";" @punctuation.delimiter)
  (do_statement ";" @punctuation.delimiter)
]
