(block) @fold
(table_values) @fold
(comment) @fold
