"""The physical model without a mesh: pass geometry, material and friction laws, thermal
properties, steel grades, interpass cooling (numpy; NGSolve only where a law is evaluated on
CoefficientFunctions). Imports: hotroll.files, hotroll.examples."""
