//! The one way in: a plant from ODE coefficients typed as text, from a plant file, from a
//! textbook model with parameters, or from a batch line — parsed here, once, for every command
//! and for the batch mode.
//!
//! ```
//! use ltikit::lti::Plant;
//! let p = Plant::from_text(Some("4"), "1 0.8 4").unwrap();
//! assert_eq!(p.name, "4 / (s^2 + 0.8 s + 4)");
//! let q = Plant::from_model("spring-mass-damper", &[("C".into(), 0.8)]).unwrap();
//! assert_eq!(q.tf().unwrap().den().coeffs(), &[1.0, 0.8, 4.0]);
//! let ss = Plant::from_matrices_text("0 1; -4 -0.8", "0; 1", "1 0", None).unwrap();
//! assert_eq!(ss.model.dims(), (1, 1));
//! assert_eq!(q.name, "spring-mass-damper (M=1, C=0.8, K=4)");
//! let r = Plant::from_json_line(r#"{"name": "p1", "den": [1, 2, 1]}"#).unwrap();
//! assert_eq!(r.name, "p1");
//! ```

pub mod diagram;
mod file;
mod located;
mod record;
mod text;

pub use file::{CoeffList, ControllerSection, MAX_RECORD_BYTES, MatrixSpec, PlantFile};
pub use located::plain;
pub use text::{
    Coefficient, coefficients_of, matrix_of_rows, parse_list, parse_matrix, parse_number,
    parse_param, parse_params, parse_values,
};

#[cfg(feature = "cli")]
pub(crate) use file::read_text;
pub use record::Plant;
pub(crate) use record::physical_model_has_no_dt;
