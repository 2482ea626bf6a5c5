//! Theory: the paper's series solution, exact periodic solutions and stick-slip boundaries.
