; A production is a scope: its predecessor's formal parameters are defined
; there and referenced in its condition, successor and probability.
(production) @local.scope
(parameters (name) @local.definition.parameter)
(define_item name: (define_name) @local.definition.constant)
(name) @local.reference
